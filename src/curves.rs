//! Curves for people to look at: the force along a quasi-static overlap path (a force-overlap loop), and
//! restitution against impact velocity by energy balance. Both write CSV with units in the header.

use crate::error::ParamError;
use crate::law::params::Effective;
use crate::law::{AnyLaw, NormalLaw};
use crate::scene::Scene;
use crate::theory::energy_balance;
use std::fmt::Write;

/// The force along a path that starts at `start` (default apart, at -|first turn|) and runs straight
/// through each turning overlap in `turns` [m], `points` states per leg. CSV: overlap, force, stiffness,
/// branch, contact state.
pub fn force_overlap_csv(scene: &Scene, start: Option<f64>, turns: &[f64], points: usize) -> Result<String, ParamError> {
    if turns.is_empty() || turns.iter().chain(&start).any(|t| !t.is_finite()) {
        return Err(ParamError::Malformed { what: "--path needs one or more finite overlaps in metres (and --start a finite one)".into() });
    }
    let law = AnyLaw::from_scene(scene)?;
    let mut h = law.initial_history();
    let mut alpha = start.unwrap_or(-turns[0].abs());
    let mut out = String::from("overlap_m,force_N,stiffness_N_per_m,branch,contact_state\n");
    let points = points.max(2);
    for &target in turns {
        let start = alpha;
        for i in 1..=points {
            alpha = start + (target - start) * i as f64 / points as f64;
            let e = law.evaluate(alpha, &h);
            h = e.history;
            let _ = writeln!(out, "{alpha:e},{:e},{:e},{:?},{}", e.force, e.stiffness, e.branch, e.branch.contact_state());
        }
    }
    Ok(out)
}

/// Restitution of undamped impacts on the wall at each velocity [m/s], by the energy balance of the
/// active law. CSV, and the sticking velocity when the velocities bracket it.
pub fn restitution_csv(scene: &Scene, velocities: &[f64]) -> Result<String, ParamError> {
    if velocities.is_empty() || velocities.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(ParamError::Malformed { what: "--velocities needs one or more positive speeds in m/s".into() });
    }
    let law = AnyLaw::from_scene(scene)?;
    let eff = Effective::from_scene(scene)?;
    let mut out = String::from("impact_velocity_m_per_s,rebound_velocity_m_per_s,restitution,max_overlap_m,max_force_N,sticks\n");
    let mut stick_bracket: Option<(f64, f64)> = None;
    let mut last: Option<(f64, bool)> = None;
    for &v in velocities {
        let o = energy_balance::impact(&law, eff.mass, v, eff.radius)
            .map_err(|e| ParamError::Inconsistent { name: "impact_velocity", why: format!("at {v} m/s: {e}") })?;
        let _ = writeln!(out, "{v:e},{:e},{:e},{:e},{:e},{}", o.rebound_velocity, o.restitution, o.max_overlap, o.max_force, o.sticks);
        if let Some((lv, ls)) = last {
            if ls && !o.sticks && stick_bracket.is_none() {
                stick_bracket = Some((lv, v));
            }
        }
        last = Some((v, o.sticks));
    }
    if let Some((lo, hi)) = stick_bracket {
        if let Some(v_s) = energy_balance::sticking_velocity(&law, eff.mass, eff.radius, lo, hi) {
            let _ = writeln!(out, "# sticking_velocity_m_per_s = {v_s:e}");
        }
    }
    Ok(out)
}
