//! The force loop: each part of the partition over its rows of the Verlet list (particle pairs) and its
//! wall contacts, one `kernel::contact` per pair, accumulating into its `Sink`. The pair loop's vector
//! arithmetic is hand-written (`dot`, `sub`, `scale`), as in the kernel, for speed (measured in
//! `bed/mod.rs`), and so is the accumulation (`Sink::add_contact`), which adds the partner's share with
//! the signs the other side of the contact gives. With AVX2 the particle pairs run four at a time on
//! lanes, with AVX-512 eight (`lanes`; 1.4-1.8 times the scalar loop for the laws evaluated on lanes
//! with AVX2, docs/benchmarks.md), over the part's near list (`near`, rebuilt here when a step cannot
//! reuse it); the wall contacts one at a time here.

use super::super::interaction::{BedLaw, Interaction};
use super::super::kernel::{contact, surface_velocity};
use super::super::neighbors::NeighborList;
use super::super::particles::Particles;
use super::super::walls::Wall;
use super::super::{cross, dot, sub, Vec3, ZERO};
use super::isa::Isa;
use super::lanes::record::{pack, Record};
use super::lanes::LaneRow;
use super::near::{self, Near};
use super::partition::{own_rows, Sink};
use super::Engine;

/// Everything the force loop reads.
struct Shared<'a, L: BedLaw> {
    p: &'a Particles,
    list: &'a NeighborList,
    pairs: &'a [Interaction<L>],
    wall_pairs: &'a [Vec<Interaction<L>>],
    walls: &'a [Wall],
    species: usize,
    dt: f64,
    /// The forgetting distance [m] (`Engine::forget`).
    forget: f64,
    /// Some sphere is held (`Engine::hold`).
    any_held: bool,
    isa: Isa,
    /// The species pairs' lane table when the pair loop runs on lanes (`lanes`), else None.
    lanes: Option<&'a [LaneRow]>,
    /// The spheres' records for eight lanes (`lanes::record`), current this step; else empty.
    records: &'a [Record],
    /// The near shell [m] (`near`).
    shell: f64,
    /// The lane loop walks every slot this step, not the near lists (`near::NearLists::walk`).
    walk: bool,
}

/// One part of the force loop: rows [rows.0, rows.1) and what it may write.
struct Part<'a, H> {
    rows: (usize, usize),
    /// The list slot of the part's first entry (its memory slices start there).
    slot0: usize,
    normal: &'a mut [H],
    spring: &'a mut [Vec3],
    radius: &'a mut [f64],
    /// Per wall: particles and their memory.
    walls: Vec<WallMemory<'a, H>>,
    sink: Sink<'a>,
    /// The part's near list (`near`), used by the lane loop; rebuilt first unless `reuse`.
    near: &'a mut Near,
    reuse: bool,
}

/// One wall's contacts: the particle of each, and their memory (law history, tangential spring, contact radius).
type WallMemory<'a, H> = (&'a [u32], &'a mut [H], &'a mut [Vec3], &'a mut [f64]);

impl<L: BedLaw> Engine<L> {
    /// The force loop over pairs and wall contacts, then (with threads) the ordered sum of the parts.
    pub fn compute_forces(&mut self) {
        self.forces_after_kick(false, false);
    }

    /// The force loop; `packed`: the step's drifting kick has just written the spheres' records (`kick`);
    /// `reuse`: the near lists hold for this step (`near::NearLists::reusable`), else the lane loop
    /// builds them first.
    pub(super) fn forces_after_kick(&mut self, packed: bool, reuse: bool) {
        let n = self.particles.len();
        // The pair loop tests each partner once against n, and the compiler drops the other bounds tests
        // (see `run_part_body`); the list must be this bed's.
        assert_eq!(self.list.rows(), n, "the Verlet list is not built for these particles");
        let record = self.record_dipoles;
        // Lanes where allowed and the pairs' laws fit them (`lanes::table`).
        #[cfg(target_arch = "x86_64")]
        let lanes = self.lanes_allowed() && super::lanes::table(&self.pairs, &mut self.lane_table);
        #[cfg(not(target_arch = "x86_64"))]
        let lanes = false;
        let records = lanes && self.records_used();
        if records && !(packed && self.records.len() == n) {
            self.pack_records();
        }
        // The near lists: reused where the step allows it (`near::NearLists::reusable`), else each part
        // builds its own first.
        let reuse = reuse && lanes && self.near.parts.len() == self.team.threads();
        self.near.parts.resize_with(self.team.threads(), Near::default);
        let shared = Shared {
            p: &self.particles,
            list: &self.list,
            pairs: &self.pairs,
            wall_pairs: &self.wall_pairs,
            walls: &self.walls,
            species: self.species,
            dt: self.dt,
            forget: self.forget,
            any_held: self.any_held,
            isa: self.isa,
            lanes: lanes.then_some(&self.lane_table[..]),
            records: if records { &self.records } else { &[] },
            shell: self.near.shell,
            walk: reuse && self.near.walk,
        };
        let mut near_parts = self.near.parts.iter_mut();
        // Cut the contact memory into the parts' pieces; each part's sink is its own rows of the totals
        // and its spill buffer (one thread: the totals).
        let mut parts: Vec<Part<L::History>> = Vec::with_capacity(self.team.threads());
        let mut normal: &mut [L::History] = &mut self.memory.history;
        let mut spring: &mut [Vec3] = &mut self.memory.spring;
        let mut radius: &mut [f64] = &mut self.memory.contact_radius;
        let mut wall_rest: Vec<WallMemory<'_, L::History>> = self
            .wall_contacts
            .iter_mut()
            .map(|wc| (&wc.particle[..], &mut wc.memory.history[..], &mut wc.memory.spring[..], &mut wc.memory.contact_radius[..]))
            .collect();
        let mut consumed = 0usize;
        let mut sinks: Vec<Sink> = if self.team.threads() == 1 {
            let t = &mut self.total;
            vec![Sink { base: 0, load: &mut t.load, spill: &mut [], dipole: &mut t.dipole, dipole_spill: &mut [], wall_force: &mut t.wall_force }]
        } else {
            // Each part's own rows of the totals, and its buffer for the spill beyond them.
            own_rows(&mut self.total, &self.parts, record)
                .into_iter()
                .zip(self.buffers.iter_mut())
                .zip(&self.parts)
                .map(|(((load, dipole), b), &base)| Sink {
                    base,
                    load,
                    spill: &mut b.load,
                    dipole,
                    dipole_spill: &mut b.dipole,
                    wall_force: &mut b.wall_force,
                })
                .collect()
        };
        for (k, sink) in sinks.drain(..).enumerate() {
            let (a, b) = (self.parts[k], self.parts[k + 1]);
            let take = self.list.start[b] as usize - consumed;
            let (mine_n, rest) = std::mem::take(&mut normal).split_at_mut(take);
            normal = rest;
            let (mine_s, rest) = std::mem::take(&mut spring).split_at_mut(take);
            spring = rest;
            let (mine_r, rest) = std::mem::take(&mut radius).split_at_mut(take);
            radius = rest;
            let mut walls = Vec::with_capacity(wall_rest.len());
            for (ps, ns, ss, rs) in wall_rest.iter_mut() {
                let cut = ps.partition_point(|&i| (i as usize) < b);
                let (p_mine, p_rest) = ps.split_at(cut);
                let (n_mine, n_rest) = std::mem::take(ns).split_at_mut(cut);
                let (s_mine, s_rest) = std::mem::take(ss).split_at_mut(cut);
                let (r_mine, r_rest) = std::mem::take(rs).split_at_mut(cut);
                walls.push((p_mine, n_mine, s_mine, r_mine));
                *ps = p_rest;
                *ns = n_rest;
                *ss = s_rest;
                *rs = r_rest;
            }
            assert!(!record || (sink.dipole.len() == sink.load.len() && sink.dipole_spill.len() == sink.spill.len()));
            let near = near_parts.next().expect("one near list per part");
            parts.push(Part { rows: (a, b), slot0: consumed, normal: mine_n, spring: mine_s, radius: mine_r, walls, sink, near, reuse });
            consumed += take;
        }
        if self.team.threads() > 1 {
            self.team.map(parts, |_, part| run_part(&shared, part));
            self.add_buffers();
        } else {
            parts.into_iter().for_each(|part| run_part(&shared, part));
        }
        for (w, wall) in self.walls.iter_mut().enumerate() {
            wall.force = self.total.wall_force[w];
        }
        // The lane loop built the near lists where it did not reuse them; the scalar loop keeps none.
        if lanes && !reuse {
            self.near.built(&self.particles.position, self.list.partner.len());
        } else if !lanes {
            self.near.valid = false;
        }
    }
}

impl<L: BedLaw> Engine<L> {
    /// The spheres' records for the lane loop (`lanes::record`), each thread packing its spheres (`sphere_cuts`).
    fn pack_records(&mut self) {
        let n = self.particles.len();
        self.records.resize(n, Record::default());
        let p = &self.particles;
        let pack_from = |first: usize, out: &mut [Record]| {
            let at = first..n;
            pack(&p.position[at.clone()], &p.velocity[at.clone()], &p.angular_velocity[at.clone()], &p.radius[at], out);
        };
        if self.team.threads() == 1 {
            pack_from(0, &mut self.records);
        } else {
            let cuts = self.sphere_cuts();
            self.team.map(super::split_at_cuts(&mut self.records, &cuts), |k, out| pack_from(cuts[k], out));
        }
    }
}

/// The force loop of one part, with the engine's instruction set.
fn run_part<L: BedLaw>(s: &Shared<L>, part: Part<L::History>) {
    // SAFETY: an engine takes an instruction set only where the CPU reports it (`Engine::set_isa`).
    #[cfg(target_arch = "x86_64")]
    match s.isa {
        Isa::Avx512 => return unsafe { run_part_avx512(s, part) },
        Isa::Avx2 => return unsafe { run_part_avx2(s, part) },
        Isa::Baseline => {}
    }
    run_part_body(s, part)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn run_part_avx2<L: BedLaw>(s: &Shared<L>, part: Part<L::History>) {
    run_part_body(s, part)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512dq")]
unsafe fn run_part_avx512<L: BedLaw>(s: &Shared<L>, part: Part<L::History>) {
    run_part_body(s, part)
}

/// The force loop of one part (compiled once per instruction set, `isa`).
#[inline(always)]
fn run_part_body<L: BedLaw>(s: &Shared<L>, part: Part<L::History>) {
    let Part { rows, slot0, normal, spring, radius, walls, mut sink, near, reuse } = part;
    sink.clear();
    let p = s.p;
    let dipoles = !sink.dipole.is_empty() || !sink.dipole_spill.is_empty();
    let (first, last) = (s.list.start[rows.0] as usize, s.list.start[rows.1] as usize);
    #[cfg(target_arch = "x86_64")]
    if let Some(table) = s.lanes {
        let input = super::lanes::LaneInput {
            spheres: super::lanes::simd::Spheres {
                position: &p.position,
                velocity: &p.velocity,
                spin: &p.angular_velocity,
                radius: &p.radius,
                species: &p.species,
                records: s.records,
            },
            species_count: s.species,
            owner: &s.list.owner,
            partner: &s.list.partner,
            table,
            pairs: s.pairs,
            dt: s.dt,
            forget: s.forget,
        };
        if !reuse {
            let build = near::Input { p, list: s.list, pairs: s.pairs, species: s.species, forget: s.forget, shell: s.shell };
            near::build(&build, first, last, slot0, normal, spring, radius, near);
        }
        // SAFETY: `lanes` is Some only on an engine whose isa is AVX2 or AVX-512, which it takes only
        // where the CPU reports it (`Engine::set_isa`).
        if !s.walk {
            unsafe {
                if s.isa == Isa::Avx512 {
                    super::lanes::near_avx512::<L>(&input, near, normal, spring, radius, &mut sink)
                } else {
                    super::lanes::near_avx2::<L>(&input, near, normal, spring, radius, &mut sink)
                }
            }
        } else {
            // SAFETY: as above.
            let done = unsafe {
                if s.isa == Isa::Avx512 {
                    super::lanes::pairs_avx512::<L>(&input, first, last, slot0, normal, spring, radius, &mut sink)
                } else {
                    super::lanes::pairs_avx2::<L>(&input, first, last, slot0, normal, spring, radius, &mut sink)
                }
            };
            // The part's last slots (fewer than a block), one at a time.
            for slot in done..last {
                let i = s.list.owner[slot] as usize;
                let m = slot - slot0;
                let row = Row::of(p, s, i);
                pair(s, &row, s.list.partner[slot] as usize, &mut normal[m], &mut spring[m], &mut radius[m], &mut sink, dipoles);
            }
        }
        walls_of_part(s, walls, &mut sink, dipoles);
        return;
    }
    let _ = (first, last, near, reuse);
    for i in rows.0..rows.1 {
        let row = Row::of(p, s, i);
        let (first, last) = (s.list.start[i] as usize, s.list.start[i + 1] as usize);
        let partners = &s.list.partner[first..last];
        let slots = first - slot0..last - slot0;
        let memory = normal[slots.clone()].iter_mut().zip(&mut spring[slots.clone()]).zip(&mut radius[slots]);
        for (&j, ((history, tangential_spring), contact_radius)) in partners.iter().zip(memory) {
            pair(s, &row, j as usize, history, tangential_spring, contact_radius, &mut sink, dipoles);
        }
    }
    walls_of_part(s, walls, &mut sink, dipoles);
}

/// What a row of the list reads of its own particle, once for all its partners.
struct Row<'a, L: BedLaw> {
    i: usize,
    x: Vec3,
    v: Vec3,
    w: Vec3,
    r: f64,
    held: bool,
    table: &'a [Interaction<L>],
}

impl<'a, L: BedLaw> Row<'a, L> {
    #[inline(always)]
    fn of(p: &Particles, s: &Shared<'a, L>, i: usize) -> Row<'a, L> {
        Row {
            i,
            x: p.position[i],
            v: p.velocity[i],
            w: p.angular_velocity[i],
            r: p.radius[i],
            held: s.any_held && p.held[i],
            table: &s.pairs[p.species[i] as usize * s.species..][..s.species],
        }
    }
}

/// One pair of the list: the row's particle and partner j, with the slot's memory.
#[inline(always)]
#[allow(clippy::too_many_arguments)] // the pair, its memory and the sink, inlined into the loops
fn pair<L: BedLaw>(
    s: &Shared<L>,
    row: &Row<L>,
    j: usize,
    history: &mut L::History,
    tangential_spring: &mut Vec3,
    contact_radius: &mut f64,
    sink: &mut Sink,
    dipoles: bool,
) {
    let p = s.p;
    let n = p.len();
    // Every per-particle array cut to n: after `j < n` below the compiler drops the other bounds tests of
    // the partner (one test instead of six per list entry).
    let (position, velocity, spin, radii, species) = (&p.position[..n], &p.velocity[..n], &p.angular_velocity[..n], &p.radius[..n], &p.species[..n]);
    let held = &p.held[..n];
    assert!(j < n);
    if row.held && held[j] {
        return; // two held spheres: neither moves, their contact and its memory stay as they are
    }
    let (i, xi, ri) = (row.i, row.x, row.r);
    let d = sub(position[j], xi);
    let dist2 = dot(d, d);
    let rj = radii[j];
    let it = &row.table[species[j] as usize];
    let range = ri + rj + it.reach;
    if dist2 >= range * range {
        let far = ri + rj + s.forget;
        if dist2 >= far * far {
            // Beyond the forgetting distance: the contact forgets (as one that never touched).
            forget(history, tangential_spring, contact_radius, it.initial);
            return;
        }
        if *tangential_spring == ZERO && (*history == it.initial || it.law.rests_apart(history)) {
            // Apart, beyond any neck, and nothing to forget or nothing the law would change (a Pasha
            // pair that touched and let go: 0.3 of 2.45 evaluated pairs per particle on the shipped
            // quarter bed, benches/engine_counts.sh).
            return;
        }
    }
    let dist = dist2.sqrt();
    let nrm = super::super::scale(d, 1.0 / dist);
    let alpha = ri + rj - dist;
    let (li, lj) = (ri - 0.5 * alpha, rj - 0.5 * alpha);
    let v = surface_velocity(row.v, row.w, li, velocity[j], spin[j], lj, nrm);
    if let Some(c) = contact(it, alpha, nrm, v, history, tangential_spring, contact_radius, s.dt) {
        // Particle j sees the contact from the other side: normal, force and tangential force
        // negated, so the same n x F_t.
        let turn = cross(nrm, c.tangential);
        sink.add_contact(i, 1.0, nrm, c.force, turn, li, c.rolling_load, dipoles);
        sink.add_contact(j, -1.0, nrm, c.force, turn, lj, c.rolling_load, dipoles);
    }
}

/// The part's wall contacts.
#[inline(always)]
fn walls_of_part<L: BedLaw>(s: &Shared<L>, walls: Vec<WallMemory<'_, L::History>>, sink: &mut Sink, dipoles: bool) {
    let p = s.p;
    for (w, (particles, normal, spring, radius)) in walls.into_iter().enumerate() {
        let wall = &s.walls[w];
        let table = &s.wall_pairs[w];
        for (slot, &i) in particles.iter().enumerate() {
            let i = i as usize;
            let ri = p.radius[i];
            let t = wall.touch(p.position[i], ri);
            let it = &table[p.species[i] as usize];
            if t.overlap < -it.reach {
                if t.overlap < -s.forget {
                    forget(&mut normal[slot], &mut spring[slot], &mut radius[slot], it.initial);
                    continue;
                }
                if spring[slot] == ZERO && (normal[slot] == it.initial || it.law.rests_apart(&normal[slot])) {
                    continue;
                }
            }
            let li = ri - 0.5 * t.overlap;
            let v = surface_velocity(p.velocity[i], p.angular_velocity[i], li, wall.velocity, ZERO, 0.0, t.normal);
            if let Some(c) = contact(it, t.overlap, t.normal, v, &mut normal[slot], &mut spring[slot], &mut radius[slot], s.dt) {
                sink.add_contact(i, 1.0, t.normal, c.force, cross(t.normal, c.tangential), li, c.rolling_load, dipoles);
                for q in 0..3 {
                    sink.wall_force[w][q] -= c.force[q];
                }
            }
        }
    }
}

/// A contact beyond the forgetting distance forgets its memory: its law's initial history, no spring, no
/// contact radius (`ContactMemory::reset`).
#[inline(always)]
pub(super) fn forget<H: Copy>(history: &mut H, spring: &mut Vec3, contact_radius: &mut f64, initial: H) {
    *history = initial;
    *spring = ZERO;
    *contact_radius = 0.0;
}
