//! The partition of the force loop over threads: the rows cut into parts of about equal work; each part
//! adds to its own particles' totals directly (no other part writes them during the loop) and to a spill
//! buffer for the particles beyond its rows that its contacts reach, [its last row + 1, last partner], with
//! no test of whose particle it is but one compare; the spills are then added, each particle's in part
//! order (its own part first, then the parts before it), so a run is bitwise the same for a given thread
//! count. With one thread the part writes the totals and spills nothing.

use super::super::interaction::BedLaw;
use super::super::{Tensor, Vec3, ZERO};
use super::Engine;

/// What the contacts of a step give one particle. One record per particle, so a contact's share is one
/// index (and one cache line) per body, and the kick reads one record. Laid out as eight f64 (force,
/// rolling load, torque, a pad), so the lane loop adds a share with one 512-bit add or two 256-bit ones
/// (`engine::lanes`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(64))]
pub struct Load {
    /// Force [N].
    pub force: Vec3,
    /// Sum of mu_r |f_n| over the contacts [N]: the load of the rolling friction (004 Table 5.3).
    pub rolling: f64,
    /// Torque about the centre [N m].
    pub torque: Vec3,
    /// Always 0.
    pad: f64,
}

const _: () = assert!(
    std::mem::offset_of!(Load, rolling) == 24 && std::mem::offset_of!(Load, torque) == 32 && std::mem::size_of::<Load>() == 64,
    "the lane loop adds [force, rolling] at offset 0 and [torque, pad] at offset 32"
);

impl Load {
    pub fn new(force: Vec3, torque: Vec3, rolling: f64) -> Load {
        Load { force, rolling, torque, pad: 0.0 }
    }
}

/// Forces accumulated by the force loop (the totals), or by one part of it (over its span of particles).
#[derive(Debug, Clone, Default)]
pub struct Accum {
    pub load: Vec<Load>,
    /// Per particle sum of |x_c - x_p| n_i F_j over its contacts (Bagi, 004 Eq. 5.1), when recorded.
    pub dipole: Vec<Tensor>,
    pub wall_force: Vec<Vec3>,
}

impl Accum {
    pub(super) fn resize(&mut self, n: usize, walls: usize, dipole: bool) {
        self.load.resize(n, Load::default());
        self.dipole.resize(if dipole { n } else { 0 }, Tensor::zeros());
        self.wall_force.resize(walls, ZERO);
    }

    /// The forces, torques and rolling loads as three arrays (a bed file's layout).
    pub fn forces(&self) -> Vec<Vec3> {
        self.load.iter().map(|l| l.force).collect()
    }

    pub fn torques(&self) -> Vec<Vec3> {
        self.load.iter().map(|l| l.torque).collect()
    }

    pub fn rolling_loads(&self) -> Vec<f64> {
        self.load.iter().map(|l| l.rolling).collect()
    }
}

/// Where one part of the force loop writes: particle i of its own rows at `load[i - base]` (a slice of
/// the totals), a particle beyond them at `spill[i - base - load.len()]` (the part's buffer), for every i
/// from its first row to its last row's last partner (j > i, so no partner is below `base`).
pub(super) struct Sink<'a> {
    pub(super) base: usize,
    pub(super) load: &'a mut [Load],
    pub(super) spill: &'a mut [Load],
    /// As `load` and `spill`, when dipoles are recorded (else both empty).
    pub(super) dipole: &'a mut [Tensor],
    pub(super) dipole_spill: &'a mut [Tensor],
    pub(super) wall_force: &'a mut [Vec3],
}

/// A sink's loads as rows of eight f64, as the lane loop adds to them (`Simd::add_shares`).
pub struct Rows<'a> {
    base: usize,
    own: &'a mut [[f64; 8]],
    spill: &'a mut [[f64; 8]],
}

impl<'a> Rows<'a> {
    pub(crate) fn new(base: usize, own: &'a mut [[f64; 8]], spill: &'a mut [[f64; 8]]) -> Rows<'a> {
        Rows { base, own, spill }
    }

    /// The row of particle i of the part's own rows (a pair's owner): no compare.
    #[inline(always)]
    pub(crate) fn own(&mut self, i: usize) -> &mut [f64; 8] {
        &mut self.own[i - self.base]
    }

    /// Particle p's row (a panic outside the part's span, as an index).
    #[inline(always)]
    pub(crate) fn at(&mut self, p: usize) -> &mut [f64; 8] {
        let o = p - self.base;
        if o < self.own.len() {
            &mut self.own[o]
        } else {
            &mut self.spill[o - self.own.len()]
        }
    }
}

impl Load {
    /// The records as rows of eight f64 (force, rolling load, torque, pad), as the lane loop adds them.
    pub(super) fn as_rows(load: &mut [Load]) -> &mut [[f64; 8]] {
        // SAFETY: a Load is eight f64 in this order with no padding (asserted above), and [f64; 8]'s
        // alignment (8) divides Load's (64); the rows borrow the records mutably for their lifetime.
        unsafe { std::slice::from_raw_parts_mut(load.as_mut_ptr() as *mut [f64; 8], load.len()) }
    }
}

impl Sink<'_> {
    pub(super) fn clear(&mut self) {
        self.load.fill(Load::default());
        self.spill.fill(Load::default());
        self.dipole.fill(Tensor::zeros());
        self.dipole_spill.fill(Tensor::zeros());
        self.wall_force.fill(ZERO);
    }

    /// The loads as the lane loop adds to them.
    pub(super) fn rows(&mut self) -> Rows<'_> {
        Rows::new(self.base, Load::as_rows(self.load), Load::as_rows(self.spill))
    }

    /// Adds one contact's share to particle `i`, seen from `i`: `n` the unit normal toward the partner,
    /// `force` its total force on `i`, `turn` = n x F_t (the same from both sides: both factors change
    /// sign), `lever` the distance from its centre to the contact point. Torque turn x lever, rolling
    /// load, and, when recorded, the dipole |x_c - x_p| n F^T of 004 Eq. 5.1. `sign` -1 gives the
    /// partner's share (its normal and force are the opposite ones): a - b is a + (-b) to the bit.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn add_contact(&mut self, i: usize, sign: f64, n: Vec3, force: Vec3, turn: Vec3, lever: f64, rolling_load: f64, dipoles: bool) {
        let o = i - self.base;
        let own = o < self.load.len();
        let l = if own { &mut self.load[o] } else { &mut self.spill[o - self.load.len()] };
        if sign > 0.0 {
            l.force.x += force.x;
            l.force.y += force.y;
            l.force.z += force.z;
        } else {
            l.force.x -= force.x;
            l.force.y -= force.y;
            l.force.z -= force.z;
        }
        l.torque.x += turn.x * lever;
        l.torque.y += turn.y * lever;
        l.torque.z += turn.z * lever;
        l.rolling += rolling_load;
        if dipoles {
            // (-n lever)(-F)^T = (n lever) F^T to the bit.
            let d = if own { &mut self.dipole[o] } else { &mut self.dipole_spill[o - self.load.len()] };
            *d += (n * lever) * force.transpose();
        }
    }
}

/// The totals cut into each part's own rows: the loads, and the dipoles where they are recorded (else
/// empty slices). `parts` holds each part's first row and, last, the row count.
pub(super) fn own_rows<'a>(total: &'a mut Accum, parts: &[usize], dipoles: bool) -> Vec<(&'a mut [Load], &'a mut [Tensor])> {
    let (mut load, mut dipole): (&mut [Load], &mut [Tensor]) = (&mut total.load, &mut total.dipole);
    let mut rows = Vec::with_capacity(parts.len().saturating_sub(1));
    for w in parts.windows(2) {
        let len = w[1] - w[0];
        let (own, rest) = std::mem::take(&mut load).split_at_mut(len);
        load = rest;
        let (own_d, rest) = std::mem::take(&mut dipole).split_at_mut(if dipoles { len } else { 0 });
        dipole = rest;
        rows.push((own, own_d));
    }
    rows
}

impl<L: BedLaw> Engine<L> {
    /// Splits the rows into `threads` parts of about equal work (list slots plus one per row); then
    /// `resize_buffers` sizes each part's spill buffer for the particles beyond its rows it touches.
    pub(super) fn cut_parts(&mut self) {
        let n = self.particles.len();
        let t = self.team.threads();
        let total = self.list.partner.len() + n;
        self.parts.clear();
        self.parts.push(0);
        let mut i = 0;
        for k in 1..t {
            let target = total * k / t;
            while i < n && (self.list.start[i] as usize + i) < target {
                i += 1;
            }
            self.parts.push(i);
        }
        self.parts.push(n);
    }

    /// The end of part k's span: one past its last row or its rows' last partner, whichever is later.
    pub(super) fn span_end(&self, k: usize) -> usize {
        let (a, b) = (self.parts[k], self.parts[k + 1]);
        (a..b).filter_map(|i| self.list.row(i).last().map(|&j| j as usize + 1)).max().unwrap_or(b).max(b)
    }

    pub(crate) fn resize_buffers(&mut self) {
        let n = self.particles.len();
        let w = self.walls.len();
        let d = self.record_dipoles;
        self.total.resize(n, w, d);
        self.span_end.clear();
        for k in 0..self.team.threads() {
            let end = self.span_end(k);
            self.span_end.push(end);
        }
        if self.team.threads() == 1 {
            // The one part writes into the totals.
            self.buffers.clear();
            return;
        }
        self.buffers.resize_with(self.team.threads(), Accum::default);
        for k in 0..self.team.threads() {
            let len = self.span_end[k] - self.parts[k + 1];
            let buffer = &mut self.buffers[k];
            buffer.load.clear();
            buffer.dipole.clear();
            buffer.resize(len, w, d);
        }
    }

    /// The totals from the parts' spills (threads > 1): each particle's own part has written it, then every
    /// earlier part whose span reaches it adds its spill, in part order; the wall reactions summed in part
    /// order. Each part's own rows are summed by a thread of their own.
    pub(super) fn add_buffers(&mut self) {
        let (parts, ends, buffers) = (&self.parts, &self.span_end, &self.buffers);
        let dipoles = self.record_dipoles;
        self.team.map(own_rows(&mut self.total, parts, dipoles), |k, (load, dipole)| {
            let a = parts[k];
            for m in 0..k {
                let end = ends[m].min(a + load.len());
                if end <= a {
                    continue;
                }
                // Part m's spill starts after its own rows.
                let from = a - parts[m + 1];
                for (t, s) in load[..end - a].iter_mut().zip(&buffers[m].load[from..]) {
                    t.force += s.force;
                    t.torque += s.torque;
                    t.rolling += s.rolling;
                }
                if dipoles {
                    for (t, s) in dipole[..end - a].iter_mut().zip(&buffers[m].dipole[from..]) {
                        *t += s;
                    }
                }
            }
        });
        let total = &mut self.total.wall_force;
        total.fill(ZERO);
        for buffer in buffers {
            for (t, f) in total.iter_mut().zip(&buffer.wall_force) {
                *t += f;
            }
        }
    }
}
