//! The near list: of the Verlet list's slots, the ones a step may have to compute, kept for as many steps
//! as no sphere has moved half of the near shell since it was built (the two-level list of the
//! issue's candidates; LAMMPS and LIGGGHTS walk the whole skin list every step).
//!
//! Why: with the skin a tenth of a diameter the list holds 3.5 slots per sphere, of which 1.7-2.3 touch
//! (docs/benchmarks.md, issue 30's eighteenth and nineteenth rounds); every step read both spheres of
//! every slot to find them. A slot is left out of the near list only where no step before the next
//! build can do anything to it, so the steps give the same bits as a walk over every slot:
//! - it is farther apart than the pair's reach plus the shell, so it cannot come within reach (each
//!   sphere moves less than half the shell, so the gap closes by less than the shell);
//! - it has no tangential spring and a history the force loop would skip apart (the initial one, or one
//!   its law `rests_apart` with: the loops visit neither beyond reach);
//! - and either it remembers nothing (forgetting is then a no-op) or it is nearer than the forgetting
//!   distance less the shell (it cannot cross that distance before the next build, so nothing forgets).
//!
//! The build applies the step's forgetting to every slot first, as the walk over every slot would.

use super::super::interaction::{BedLaw, Interaction};
use super::super::neighbors::NeighborList;
use super::super::particles::Particles;
use super::super::{dot, sub, Vec3, ZERO};
use super::force_loop::forget;

/// One part's near slots, in slot order, with the spheres and species pair of each (so a step reads
/// neither the list nor the species again).
#[derive(Debug, Clone, Default)]
pub struct Near {
    /// The slot, relative to the part's first (its memory slices start there).
    pub slot: Vec<u32>,
    pub i: Vec<u32>,
    pub j: Vec<u32>,
    /// The species pair's index into the interaction table.
    pub pair: Vec<u32>,
}

#[allow(clippy::len_without_is_empty)] // a count of slots; nothing asks whether there are none
impl Near {
    pub fn len(&self) -> usize {
        self.slot.len()
    }

    fn memory_bytes(&self) -> usize {
        4 * (self.slot.capacity() + self.i.capacity() + self.j.capacity() + self.pair.capacity())
    }

    fn clear(&mut self) {
        self.slot.clear();
        self.i.clear();
        self.j.clear();
        self.pair.clear();
    }

    fn push(&mut self, m: usize, i: usize, j: usize, pair: usize) {
        self.slot.push(m as u32);
        self.i.push(i as u32);
        self.j.push(j as u32);
        self.pair.push(pair as u32);
    }
}

/// The engine's near lists: one per part of the force loop, the positions they were built at, the shell.
#[derive(Debug, Clone, Default)]
pub struct NearLists {
    pub parts: Vec<Near>,
    /// The spheres' positions at the last build (the kick measures how far each has moved since).
    pub reference: Vec<Vec3>,
    /// The near shell [m]: how much farther than its reach a pair is kept.
    pub shell: f64,
    /// The lists hold what the rules above say for the engine's list, memory and interactions. Anything
    /// that changes those other than a step (a list rebuild, new interactions, a loaded or restored
    /// memory, a force pass whose memory is put back) clears it.
    pub valid: bool,
    /// Builds so far.
    pub builds: u64,
    /// The last build kept more than `WALK` of the slots: until the Verlet list is rebuilt the lane loop
    /// walks every slot instead (the near loop reads each slot's memory by index, the walk in place; on
    /// the shipped quarter, 92 % kept, the walk was the faster), and the kick measures no displacement
    /// for the near lists.
    pub walk: bool,
}

/// The share of the Verlet list's slots above which the lane loop walks every slot (`NearLists::walk`).
/// On the shipped quarter (92 % kept, skin 0.025 d) the near loop ran at 0.96x the walk, on the LAMMPS
/// bench bed (74 %, skin 0.1 d) at 1.08-1.21x (issue 30's nineteenth round).
const WALK: f64 = 0.85;

impl NearLists {
    /// Whether a step may reuse the lists: built, and walking or no sphere has moved `0.45 shell` since
    /// (`moved2`, the largest squared displacement from `reference`). 0.45 rather than 0.5: rounding of
    /// the positions and the kick's sum is far below that margin.
    pub fn reusable(&self, moved2: f64) -> bool {
        let limit = 0.45 * self.shell;
        self.valid && (self.walk || moved2 <= limit * limit)
    }

    /// Bytes held by the lists and the reference positions.
    pub fn memory_bytes(&self) -> usize {
        self.parts.iter().map(Near::memory_bytes).sum::<usize>() + self.reference.capacity() * std::mem::size_of::<Vec3>()
    }

    /// The reference positions the kick measures from, empty when nothing needs them.
    pub fn kick_reference(&self) -> &[Vec3] {
        if self.valid && !self.walk {
            &self.reference
        } else {
            &[]
        }
    }

    /// The lists were built at `position` over a list of `slots` slots: valid, and walking if they keep
    /// most of the slots.
    pub fn built(&mut self, position: &[Vec3], slots: usize) {
        let kept: usize = self.parts.iter().map(|p| p.len()).sum();
        self.walk = kept as f64 > WALK * slots as f64;
        self.reference.clear();
        if !self.walk {
            self.reference.extend_from_slice(position);
        }
        self.valid = true;
        self.builds += 1;
    }
}

/// What the build reads of the engine.
pub struct Input<'a, L: BedLaw> {
    pub p: &'a Particles,
    pub list: &'a NeighborList,
    pub pairs: &'a [Interaction<L>],
    pub species: usize,
    pub forget: f64,
    pub shell: f64,
}

/// Builds the near list of slots [first, last) (the part's first slot `slot0`), forgetting what is beyond
/// the forgetting distance as the step's force loop would.
#[allow(clippy::too_many_arguments)] // the part's slots, its memory and its list
pub fn build<L: BedLaw>(
    e: &Input<L>,
    first: usize,
    last: usize,
    slot0: usize,
    normal: &mut [L::History],
    spring: &mut [Vec3],
    radius: &mut [f64],
    out: &mut Near,
) {
    out.clear();
    let p = e.p;
    let n = p.len();
    let (position, radii, species) = (&p.position[..n], &p.radius[..n], &p.species[..n]);
    for slot in first..last {
        let (i, j) = (e.list.owner[slot] as usize, e.list.partner[slot] as usize);
        let pair = species[i] as usize * e.species + species[j] as usize;
        let it = &e.pairs[pair];
        let m = slot - slot0;
        let d = sub(position[j], position[i]);
        let dist2 = dot(d, d);
        let sum_r = radii[i] + radii[j];
        let far = sum_r + e.forget;
        if dist2 >= far * far {
            forget(&mut normal[m], &mut spring[m], &mut radius[m], it.initial);
        }
        let near = sum_r + it.reach + e.shell;
        let quiet = spring[m] == ZERO && (normal[m] == it.initial || it.law.rests_apart(&normal[m]));
        let keep = if dist2 < near * near || !quiet {
            true
        } else if normal[m] == it.initial && radius[m] == 0.0 {
            false
        } else {
            // Remembers something it would forget beyond the forgetting distance: kept unless it is too
            // far inside it to get there before the next build.
            let inside = sum_r + e.forget - e.shell;
            !(inside > 0.0 && dist2 < inside * inside)
        };
        if keep {
            out.push(m, i, j, pair);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bed::any::interactions;
    use crate::bed::scene::BedScene;
    use crate::law::pasha::PashaHistory;
    use crate::law::pasha_simplified::PashaSimplified;
    use crate::law::NormalLaw;

    /// Which of one pair's states the build keeps, at gap `gap` [m] (surface to surface).
    fn kept(gap: f64, history: PashaHistory, spring: Vec3, forget: f64, shell: f64) -> (bool, PashaHistory) {
        let scene = BedScene::from_json(r#"{"particle_particle": {"contact_model": "pasha_simplified", "particle_yield_pressure": 1e8}}"#).unwrap();
        let (pairs, _) = interactions::<PashaSimplified>(&scene, &[]).unwrap();
        let r = 0.5e-3;
        let mut p = Particles::default();
        p.push(Vec3::new(0.0, 0.0, 0.0), r, 2500.0, 0);
        p.push(Vec3::new(2.0 * r + gap, 0.0, 0.0), r, 2500.0, 0);
        let mut list = NeighborList::new(1e-3);
        list.build(&p.position, &p.radius);
        assert_eq!(list.partner.len(), 1);
        let e = Input { p: &p, list: &list, pairs: &pairs, species: 1, forget, shell };
        let (mut normal, mut spring, mut radius) = (vec![history], vec![spring], vec![0.0]);
        let mut out = Near::default();
        build(&e, 0, 1, 0, &mut normal, &mut spring, &mut radius, &mut out);
        (out.len() == 1, normal[0])
    }

    #[test]
    fn a_slot_is_left_out_only_where_no_step_before_the_next_build_can_change_it() {
        let scene = BedScene::from_json(r#"{"particle_particle": {"contact_model": "pasha_simplified", "particle_yield_pressure": 1e8}}"#).unwrap();
        let (pairs, _) = interactions::<PashaSimplified>(&scene, &[]).unwrap();
        let (initial, reach) = (pairs[0].initial, pairs[0].reach);
        let (forget, shell) = (20e-6, 2e-6);
        // A pair that touched and let go: apart, remembering its largest plastic overlap.
        let detached = PashaHistory { established: false, alpha_max: 1e-7 };
        assert!(pairs[0].law.rests_apart(&detached) && detached != initial);
        let touching = PashaHistory { established: true, alpha_max: 1e-7 };
        let (none, spring) = (ZERO, Vec3::new(1e-9, 0.0, 0.0));
        let band = reach + shell + 0.5 * (forget - 2.0 * shell - reach);
        // Fresh: kept within reach plus the shell, left out beyond.
        assert!(kept(reach + 0.5 * shell, initial, none, forget, shell).0);
        assert!(!kept(reach + 1.5 * shell, initial, none, forget, shell).0);
        // Something to compute: an established contact or a spring, kept wherever it is not forgotten.
        assert!(kept(band, touching, none, forget, shell).0);
        assert!(kept(band, initial, spring, forget, shell).0);
        // Detached: left out where it cannot reach the forgetting distance before the next build, kept
        // within a shell of it (a step may have to forget it).
        assert!(!kept(band, detached, none, forget, shell).0);
        assert!(kept(forget - 0.5 * shell, detached, none, forget, shell).0);
        // Beyond the forgetting distance: forgotten at the build, as the step would, then left out.
        let (k, h) = kept(forget + 1.5 * shell, detached, none, forget, shell);
        assert!(!k && h == initial);
        // Forgotten but still within the shell of it (it may come back): fresh, beyond reach, so left out.
        assert!(!kept(forget + 0.5 * shell, detached, none, forget, shell).0);
    }
}
