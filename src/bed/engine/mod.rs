//! The DEM engine for one normal law: the time step of the bed, velocity Verlet (kick, drift, forces, kick;
//! symplectic for the conservative forces, as LAMMPS' `fix nve/sphere`), with the Verlet list rebuilt on
//! displacement. One job a file:
//! - here: the engine, its set-up and the integration (kicks, drift, walls, when to rebuild);
//! - `memory`: carrying every contact's memory (law history, tangential spring, contact radius) across
//!   list rebuilds;
//! - `partition`: the fixed partition of the particles into parts of equal work, each part adding its
//!   own rows into the totals and the particles beyond them into its spill buffer, and the spills
//!   added in part order, so a run is bitwise the same for a given thread count;
//! - `force_loop`: the force loop of one part over its pairs and wall contacts;
//! - `isa`: the instruction set the force loop and the kick run with (AVX-512 or AVX2 where the CPU
//!   has it);
//! - `near`: the slots the lane loop computes, kept across steps while no sphere has moved far enough
//!   for a slot left out to matter;
//! - `lanes`: the pair loop on lanes, four contacts at once with AVX2 and eight with AVX-512, for the
//!   laws that have it; the kick on AVX2 lanes, four spheres at once (`lanes/kick.rs`); the spheres'
//!   records that eight lanes read, written by the drifting kick (`lanes/record.rs`).

mod contact_memory;
mod force_loop;
mod isa;
mod lanes;
mod memory;
pub(crate) mod near;
mod partition;

pub use contact_memory::ContactMemory;
pub use isa::Isa;
pub use lanes::LaneLaw;
pub use memory::WallContacts;
pub use partition::{Accum, Load};

use super::interaction::{BedLaw, Interaction};
use super::neighbors::NeighborList;
use super::particles::Particles;
use super::team::Team;
use super::walls::Wall;
use super::{Tensor, Vec3, ZERO};
use crate::law;

/// The DEM engine for one normal law `L` (particle-particle and particle-wall contacts both use it,
/// each pair of species and each species-wall pair with its own parameters).
pub struct Engine<L: BedLaw> {
    /// The spheres.
    pub particles: Particles,
    /// The walls, in the order of `wall_pairs` and `wall_contacts`.
    pub walls: Vec<Wall>,
    /// Interactions of species pairs, `pairs[a * species + b]` (`pair(a, b)`).
    pub pairs: Vec<Interaction<L>>,
    /// Interactions of each wall with each species, `wall_pairs[w][s]`.
    pub wall_pairs: Vec<Vec<Interaction<L>>>,
    /// Number of species (size classes).
    pub species: usize,
    /// Gravitational acceleration [m/s^2].
    pub gravity: Vec3,
    /// Time step [s].
    pub dt: f64,
    /// Simulated time [s].
    pub time: f64,
    /// Steps taken.
    pub steps: u64,
    /// The Verlet neighbour list of particle pairs.
    pub list: NeighborList,
    /// What each list slot's contact remembers: law history, tangential spring, contact radius.
    pub memory: ContactMemory<L::History>,
    /// Each wall's contacts: the particles within range of it and their memory.
    pub wall_contacts: Vec<WallContacts<L::History>>,
    /// Wall positions at the last rebuild.
    wall_reference: Vec<Vec3>,
    /// Largest reach of any interaction [m].
    reach: f64,
    /// The forgetting distance [m]: a contact whose surfaces are farther apart than this forgets its
    /// memory at that step (as one that never touched), whatever the skin (docs/bed.md).
    forget: f64,
    /// Forces, torques, rolling loads (and dipoles) of the last step.
    total: Accum,
    /// Each part's spill buffer, over the particles beyond its rows that it reaches, and its wall
    /// reactions (threads > 1; one thread writes into `total`).
    buffers: Vec<Accum>,
    /// First row of each part of the force loop (len parts + 1).
    parts: Vec<usize>,
    /// One past the last particle each part writes (its last row or its rows' last partner).
    span_end: Vec<usize>,
    /// The threads of the parallel phases (the caller's and its helpers).
    team: Team,
    record_dipoles: bool,
    /// The force on each held sphere when it was held (`hold`).
    held_reference: Vec<Vec3>,
    /// False when no sphere is held: the force loop and the kick then skip the test.
    any_held: bool,
    /// The instruction set of the force loop and the kick.
    isa: Isa,
    /// The species pairs' parameters as the lane loop reads them, rebuilt by each force loop that runs on
    /// lanes (`lanes::table`).
    lane_table: Vec<lanes::LaneRow>,
    /// The spheres' records for the pair loop on eight lanes (`lanes::record`), written by each step's
    /// drifting kick (else packed by the force loop); unused on four lanes and on the scalar loop.
    records: Vec<lanes::record::Record>,
    /// The slots the lane loop computes, kept across steps (`near`).
    pub(crate) near: near::NearLists,
}

impl<L: BedLaw> std::fmt::Debug for Engine<L> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Engine({} particles, {} walls, {} threads)", self.particles.len(), self.walls.len(), self.team.threads())
    }
}

impl<L: BedLaw> Engine<L> {
    /// The interaction of a sphere of species `a` with one of species `b`.
    pub fn pair(&self, a: usize, b: usize) -> &Interaction<L> {
        &self.pairs[a * self.species + b]
    }

    /// An engine over these particles and walls. `threads` >= 1; more than one starts a pool the engine
    /// owns. The skin and the forgetting distance must exceed every interaction's reach.
    #[allow(clippy::too_many_arguments)] // the engine's whole set-up, each argument named at the one call site
    pub fn new(
        particles: Particles,
        walls: Vec<Wall>,
        pairs: Vec<Interaction<L>>,
        wall_pairs: Vec<Vec<Interaction<L>>>,
        species: usize,
        gravity: Vec3,
        dt: f64,
        skin: f64,
        forget: f64,
        threads: usize,
    ) -> Result<Engine<L>, String> {
        assert_eq!(pairs.len(), species * species);
        assert_eq!(wall_pairs.len(), walls.len());
        if particles.species.iter().any(|&s| s as usize >= species) {
            return Err("a particle has a species beyond the interaction table".into());
        }
        let reach = pairs.iter().chain(wall_pairs.iter().flatten()).map(|it| it.reach).fold(0.0, f64::max);
        beyond_reach("the bed's", reach, skin, forget)?;
        if !(1..=256).contains(&threads) {
            return Err(format!("threads = {threads} is out of range: allowed [1, 256]"));
        }
        let team = Team::new(threads)?;
        let n_walls = walls.len();
        let mut e = Engine {
            particles,
            wall_contacts: (0..n_walls).map(|_| WallContacts::new()).collect(),
            wall_reference: walls.iter().map(|w| w.position).collect(),
            walls,
            pairs,
            wall_pairs,
            species,
            gravity,
            dt,
            time: 0.0,
            steps: 0,
            list: NeighborList::new(skin),
            memory: ContactMemory::default(),
            reach,
            forget,
            total: Accum::default(),
            buffers: vec![],
            parts: vec![],
            span_end: vec![],
            team,
            record_dipoles: false,
            held_reference: vec![],
            any_held: false,
            isa: Isa::detect(),
            lane_table: vec![],
            records: vec![],
            near: near::NearLists { shell: near_shell(skin, forget), ..Default::default() },
        };
        e.rebuild();
        e.compute_forces();
        Ok(e)
    }

    /// Number of threads the force loop and the kick run on (1: no pool).
    pub fn threads(&self) -> usize {
        self.team.threads()
    }

    /// The instruction set the force loop and the kick run with.
    pub fn isa(&self) -> Isa {
        self.isa
    }

    /// How the force loop runs the particle pairs now: `vector` (the law on lanes), `per_lane` (the
    /// law once per lane, the rest on lanes) or `scalar` (`lanes`).
    pub fn pair_loop(&self) -> &'static str {
        #[cfg(target_arch = "x86_64")]
        if self.lanes_allowed() && lanes::table(&self.pairs, &mut Vec::new()) {
            return match L::LANES {
                lanes::Lanes::Vector => "vector",
                lanes::Lanes::PerLane => "per_lane",
            };
        }
        "scalar"
    }

    /// Whether this force loop may run the pairs on lanes, the law and its pairs aside: AVX2 or AVX-512, and neither
    /// held spheres nor the dipole pass (both stay on the scalar loop).
    pub(super) fn lanes_allowed(&self) -> bool {
        self.isa != Isa::Baseline && !self.any_held && !self.record_dipoles
    }

    /// Whether the pair loop may run on eight lanes, which read the spheres' records (`lanes::record`).
    pub(super) fn records_used(&self) -> bool {
        self.isa == Isa::Avx512 && self.lanes_allowed()
    }

    /// Runs the hot loops with another instruction set (the same bits either way; for comparisons).
    /// Refused where this CPU lacks it.
    pub fn set_isa(&mut self, isa: Isa) -> Result<(), String> {
        if !isa.available() {
            return Err(format!("this CPU cannot run the engine's {} loops", isa.name()));
        }
        self.isa = isa;
        Ok(())
    }

    /// Adds a wall (the indenter lowered onto a prepared bed) with its interaction with each species,
    /// keeping every contact's memory: the bed goes on as it was, now with the wall. Refused when the
    /// wall's necks reach beyond the skin.
    pub fn add_wall(&mut self, wall: Wall, row: Vec<Interaction<L>>) -> Result<(), String> {
        self.reach_for(&wall.name, &row)?;
        self.wall_reference.push(wall.position);
        self.walls.push(wall);
        self.wall_pairs.push(row);
        self.wall_contacts.push(WallContacts::new());
        // The forces of the last step stay as they are (the next half kick needs the ones the drift was
        // made with); the wall's own contacts enter at the next force loop.
        self.rebuild();
        Ok(())
    }

    /// Gives wall `w` new interactions (the test's own walls, or a restored indenter's), keeping every
    /// contact's memory. Refused when the wall's necks reach beyond the skin.
    pub fn set_wall_row(&mut self, w: usize, row: Vec<Interaction<L>>) -> Result<(), String> {
        let name = self.walls[w].name.clone();
        self.reach_for(&name, &row)?;
        self.wall_pairs[w] = row;
        Ok(())
    }

    /// Gives every pair of species and every wall new interactions of the same law (a one-change
    /// experiment on a prepared bed: less damping, no rolling friction, no cohesion), keeping every
    /// contact's memory. Refused when the tables do not fit the bed or an adhesive neck would reach
    /// beyond the skin.
    pub fn set_interactions(&mut self, pairs: Vec<Interaction<L>>, wall_pairs: Vec<Vec<Interaction<L>>>) -> Result<(), String> {
        if pairs.len() != self.species * self.species || wall_pairs.len() != self.walls.len() || wall_pairs.iter().any(|r| r.len() != self.species) {
            return Err("the interaction tables do not fit this bed's species and walls".into());
        }
        let reach = pairs.iter().chain(wall_pairs.iter().flatten()).map(|it| it.reach).fold(0.0, f64::max);
        beyond_reach("the changed law's", reach, self.list.skin, self.forget)?;
        // A pair that never touched holds its law's initial history, which may depend on the changed
        // parameters (Pasha's alpha_0 on f_ce): it takes the new one; every other memory stays.
        let s = self.species;
        let sp = &self.particles.species;
        for i in 0..self.list.rows() {
            let a = sp[i] as usize;
            for (k, &j) in (self.list.start[i] as usize..).zip(self.list.row(i)) {
                let b = sp[j as usize] as usize;
                if self.memory.history[k] == self.pairs[a * s + b].initial {
                    self.memory.history[k] = pairs[a * s + b].initial;
                }
            }
        }
        for (w, wc) in self.wall_contacts.iter_mut().enumerate() {
            for (k, &i) in wc.particle.iter().enumerate() {
                let a = sp[i as usize] as usize;
                if wc.memory.history[k] == self.wall_pairs[w][a].initial {
                    wc.memory.history[k] = wall_pairs[w][a].initial;
                }
            }
        }
        self.pairs = pairs;
        self.wall_pairs = wall_pairs;
        self.reach = reach;
        self.near.valid = false;
        Ok(())
    }

    /// A new Verlet skin [m] for the rest of the run, the list rebuilt at once with every contact's
    /// memory carried (a contact that remembers stays in the list until it is beyond the forgetting
    /// distance). Refused when it does not exceed the adhesive necks' reach. The skin changes which pairs
    /// the list holds, not what any contact remembers: one thread steps to the same bits under any skin
    /// above the reach, for every law (docs/bed.md).
    pub fn set_skin(&mut self, skin: f64) -> Result<(), String> {
        if !skin.is_finite() {
            return Err(format!("skin = {skin:e} m must be finite"));
        }
        beyond_reach("the bed's", self.reach, skin, self.forget)?;
        if skin != self.list.skin {
            self.list.skin = skin;
            self.near.shell = near_shell(skin, self.forget);
            self.rebuild();
        }
        Ok(())
    }

    /// A new forgetting distance [m] (`forget`), from the next force loop on: a contact whose surfaces
    /// are farther apart forgets its memory (the plastic history of Pasha's and Nan's laws, a tangential
    /// spring). Refused when it does not exceed the adhesive necks' reach (a neck that still pulls must
    /// not forget).
    pub fn set_forgetting_distance(&mut self, forget: f64) -> Result<(), String> {
        if !forget.is_finite() {
            return Err(format!("forgetting_distance = {forget:e} m must be finite"));
        }
        beyond_reach("the bed's", self.reach, self.list.skin, forget)?;
        self.forget = forget;
        self.near.shell = near_shell(self.list.skin, forget);
        self.near.valid = false;
        Ok(())
    }

    /// The forgetting distance [m].
    pub fn forgetting_distance(&self) -> f64 {
        self.forget
    }

    /// Widens the engine's reach to a wall's new interactions (one per species), refused when its
    /// adhesive necks would reach beyond the skin or the forgetting distance.
    fn reach_for(&mut self, wall: &str, row: &[Interaction<L>]) -> Result<(), String> {
        assert_eq!(row.len(), self.species);
        let reach = row.iter().map(|it| it.reach).fold(self.reach, f64::max);
        beyond_reach(&format!("wall `{wall}`'s"), reach, self.list.skin, self.forget)?;
        self.reach = reach;
        Ok(())
    }

    /// The forces of the last step.
    pub fn totals(&self) -> &Accum {
        &self.total
    }

    /// Sets the forces of the last step (a bed loaded from a file continues exactly).
    pub fn set_totals(&mut self, force: &[Vec3], torque: &[Vec3], rolling: &[f64]) {
        assert!(
            force.len() == self.total.load.len() && torque.len() == force.len() && rolling.len() == force.len(),
            "one force, torque and rolling load per sphere"
        );
        for (l, ((f, t), r)) in self.total.load.iter_mut().zip(force.iter().zip(torque).zip(rolling)) {
            *l = Load::new(*f, *t, *r);
        }
    }

    /// Per particle sum of |x_c - x_p| n_i F_j over its contacts (Bagi, 004 Eq. 5.1) for the current
    /// state. The force loop runs once more with a zero spring increment, which reproduces the last
    /// step's forces and leaves every history as it was.
    pub fn measure_dipoles(&mut self) -> Vec<Tensor> {
        // The forces of the last step are kept as they were: the next half kick needs them (the pass
        // here sees the velocities after the step, not the ones the step's damping saw).
        let total = self.total.clone();
        let wall_force: Vec<Vec3> = self.walls.iter().map(|w| w.force).collect();
        self.record_dipoles = true;
        self.resize_buffers();
        self.compute_forces_without_increment();
        let dipoles = std::mem::take(&mut self.total.dipole);
        self.record_dipoles = false;
        self.total = total;
        self.resize_buffers();
        for (w, f) in self.walls.iter_mut().zip(wall_force) {
            w.force = f;
        }
        dipoles
    }

    /// The force loop with a zero tangential increment: the forces of the current state, with every
    /// contact's memory left exactly as it is.
    pub fn compute_forces_without_increment(&mut self) {
        // The pass re-projects springs onto the tangent plane and the Coulomb limit, which moves them by
        // rounding; the memory is put back as it was so the pass leaves no trace.
        let memory = self.memory.clone();
        let walls: Vec<_> = self.wall_contacts.iter().map(|w| w.memory.clone()).collect();
        let dt = self.dt;
        self.dt = 0.0;
        self.compute_forces();
        self.dt = dt;
        self.memory = memory;
        // The near lists were built on the memory the pass left.
        self.near.valid = false;
        for (w, m) in self.wall_contacts.iter_mut().zip(walls) {
            w.memory = m;
        }
    }

    /// One step of velocity Verlet.
    pub fn step(&mut self) {
        self.step_parts(false, false);
    }

    /// Holds the spheres marked in `held` where they are, at rest, until disturbed (`release_disturbed`):
    /// a held sphere does not move, and the contacts between two held spheres are not computed (their
    /// memory stays as it is: neither moves). Everything a moving sphere feels is unchanged. Used by the
    /// indentation's `fidelity = fast` for the spheres far from the indenter.
    pub fn hold(&mut self, held: &[bool]) {
        assert_eq!(held.len(), self.particles.len(), "one flag per sphere");
        for (i, &h) in held.iter().enumerate() {
            if h {
                self.particles.velocity[i] = ZERO;
                self.particles.angular_velocity[i] = ZERO;
            }
        }
        self.particles.held = held.to_vec();
        self.any_held = held.iter().any(|&h| h);
        self.held_reference = self.partial_forces();
    }

    /// The forces of one pass without increments, the totals of the last step left as they were.
    fn partial_forces(&mut self) -> Vec<Vec3> {
        let saved = self.total.clone();
        self.compute_forces_without_increment();
        let forces = self.total.forces();
        self.total = saved;
        forces
    }

    /// Releases every held sphere whose force from its moving neighbours and the walls has changed by more
    /// than `threshold` [N] since it was held; the released then move with the complete forces of the
    /// current state. Returns how many were released.
    pub fn release_disturbed(&mut self, threshold: f64) -> usize {
        let mut released = 0;
        for i in 0..self.particles.len() {
            if self.particles.held[i] && (self.total.load[i].force - self.held_reference[i]).norm_squared() > threshold * threshold {
                self.particles.held[i] = false;
                released += 1;
            }
        }
        self.any_held = self.particles.held.iter().any(|&h| h);
        if released > 0 {
            // The last step's totals of a released sphere miss its contacts with held neighbours.
            self.compute_forces_without_increment();
        }
        released
    }

    /// The force on each sphere when it was held (for a saved state).
    pub fn held_reference(&self) -> &[Vec3] {
        &self.held_reference
    }

    /// Puts back held spheres and their reference forces from a saved state.
    pub fn restore_held(&mut self, held: Vec<bool>, reference: Vec<Vec3>) {
        assert!(held.len() == self.particles.len() && reference.len() == held.len(), "one flag and force per sphere");
        self.any_held = held.iter().any(|&h| h);
        self.particles.held = held;
        self.held_reference = reference;
    }

    /// Several steps.
    pub fn run(&mut self, steps: u64) {
        for k in 0..steps {
            self.step_parts(k > 0, k + 1 < steps);
        }
    }

    /// Steps until `go_on`, called after each step with the walls (their forces those of that step) and
    /// the time, says stop, or `steps` are done; returns the steps taken. The same steps to the bit as
    /// `step` called as often, in one pool install (a test that reads a wall at every step: unconfined
    /// compression). Between the calls the spheres' velocities are half a kick short (the kicks of two
    /// steps are fused as in `run`): `go_on` reads the walls only.
    pub fn run_while(&mut self, steps: u64, mut go_on: impl FnMut(&[Wall], f64) -> bool + Send) -> u64 {
        if steps == 0 {
            return 0;
        }
        let mut taken = 0;
        loop {
            self.step_parts(taken > 0, true);
            taken += 1;
            if !go_on(&self.walls, self.time) || taken == steps {
                // The closing half kick the last step left open.
                self.kick(0.5 * self.dt, false, false);
                return taken;
            }
        }
    }

    /// One step of velocity Verlet. `closed_before`: the last step left its closing half kick to this
    /// one; `leave_open`: leave this step's closing half kick to the next. Both half kicks between two
    /// steps use the same forces, so the two are one pass over the spheres, with the same arithmetic for
    /// each sphere in the same order as two: the same bits, and the kicks' instructions per
    /// particle-step 132 -> 112 (Cachegrind, quarter bed, `pasha_simplified`).
    fn step_parts(&mut self, closed_before: bool, leave_open: bool) {
        let h = 0.5 * self.dt;
        // Rebuild when a particle or a wall has moved half of (skin - reach): no pair can then have
        // closed the whole margin unseen.
        let limit = 0.5 * (self.list.skin - self.reach);
        let (moved, moved_near) = self.kick(h, true, closed_before);
        let packed = self.records_used();
        self.move_walls();
        let wall_moved = self.walls.iter().zip(&self.wall_reference).any(|(w, r)| (w.position - r).norm_squared() > limit * limit);
        if wall_moved || moved > limit * limit || self.list.rows() != self.particles.len() {
            self.rebuild();
        }
        let reuse = self.near.reusable(moved_near);
        self.forces_after_kick(packed, reuse);
        if !leave_open {
            self.kick(h, false, false);
        }
        self.time += self.dt;
        self.steps += 1;
    }

    /// Half a kick: v += (F/m + g) h, w += T/I h, and rolling friction against the spin; with `drift`
    /// also x += v dt; with `twice`, two half kicks before the drift (the last step's closing one and
    /// this step's opening one). Returns the largest squared displacements since the last list build and
    /// since the last near list build (with drift; infinite for the near list when it is not valid). A drifting kick on an engine that may run its pairs on eight lanes also writes the
    /// spheres' records for them (`lanes::record`), saving the force loop a pass over every sphere.
    fn kick(&mut self, h: f64, drift: bool, twice: bool) -> (f64, f64) {
        let threads = self.team.threads();
        let cuts = if threads > 1 { self.sphere_cuts() } else { vec![] };
        let write_records = drift && self.records_used();
        let load = &self.total.load[..];
        let p = &mut self.particles;
        let reference = self.list.reference();
        let near_reference: &[Vec3] = self.near.kick_reference();
        let dt = if drift { self.dt } else { 0.0 };
        let g = self.gravity;
        let any_held = self.any_held;
        let body = Body { inv_mass: &p.inv_mass, inv_inertia: &p.inv_inertia, radius: &p.radius, held: if any_held { &p.held } else { &[] } };
        let records: &mut [lanes::record::Record] = if write_records {
            self.records.resize(p.len(), Default::default());
            &mut self.records
        } else {
            &mut []
        };
        let isa = self.isa;
        let halves = if twice { 2 } else { 1 };
        let kick = Kick { g, h, halves, dt };
        let refs = References { list: reference, near: near_reference };
        if threads == 1 {
            return kick_range(isa, 0, &mut p.velocity, &mut p.angular_velocity, &mut p.position, body, load, refs, kick, records);
        }
        let records: Vec<&mut [lanes::record::Record]> =
            if records.is_empty() { (0..threads).map(|_| &mut [][..]).collect() } else { split_at_cuts(records, &cuts) };
        let chunks: Vec<_> = split_at_cuts(&mut p.velocity, &cuts)
            .into_iter()
            .zip(split_at_cuts(&mut p.angular_velocity, &cuts))
            .zip(split_at_cuts(&mut p.position, &cuts))
            .zip(records)
            .collect();
        self.team
            .map(chunks, |k, (((v, w), x), out)| kick_range(isa, cuts[k], v, w, x, body, load, refs, kick, out))
            .into_iter()
            .fold((0.0, 0.0), |a, b| (a.0.max(b.0), a.1.max(b.1)))
    }

    /// Where the spheres are cut among the threads for the kick and the records: each thread takes the spheres
    /// of its part of the force loop (whose loads it has just summed, still in its core's cache); before the
    /// first cut of the parts, equal chunks. Which thread handles a sphere does not change its bits.
    fn sphere_cuts(&self) -> Vec<usize> {
        let (n, threads) = (self.particles.len(), self.team.threads());
        if self.parts.len() == threads + 1 && self.parts[threads] == n {
            self.parts.clone()
        } else {
            (0..=threads).map(|k| n * k / threads).collect()
        }
    }

    fn move_walls(&mut self) {
        for w in &mut self.walls {
            w.position += w.velocity * self.dt;
        }
    }

    /// Bytes held by the engine's arrays (particles, list, contact memory, near lists, buffers).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let (v, u) = (size_of::<Vec3>(), size_of::<u32>());
        let acc = |a: &Accum| a.load.capacity() * size_of::<Load>() + a.wall_force.capacity() * v + a.dipole.capacity() * size_of::<Tensor>();
        self.particles.memory_bytes()
            + self.list.memory_bytes()
            + self.memory.memory_bytes()
            + self.wall_contacts.iter().map(|w| w.particle.capacity() * u + w.memory.memory_bytes()).sum::<usize>()
            + self.buffers.iter().map(acc).sum::<usize>()
            + acc(&self.total)
            + self.near.memory_bytes()
    }

    /// The particle-particle pairs in contact now: (i, j, overlap [m]).
    fn touching(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let p = &self.particles;
        (0..self.list.rows()).flat_map(move |i| {
            (self.list.start[i] as usize..).zip(self.list.row(i)).filter_map(move |(k, &j)| {
                let j = j as usize;
                let alpha = p.radius[i] + p.radius[j] - (p.position[j] - p.position[i]).norm();
                let it = self.pair(p.species[i] as usize, p.species[j] as usize);
                law::NormalLaw::evaluate(&it.law, alpha, &self.memory.history[k]).branch.in_contact().then_some((i, j, alpha))
            })
        })
    }

    /// Contacts carrying force now, and their mean overlap [m] (particle-particle only).
    pub fn contact_statistics(&self) -> (usize, f64) {
        let (count, sum) = self.touching().fold((0usize, 0.0), |(c, s), (_, _, alpha)| (c + 1, s + alpha));
        (count, if count > 0 { sum / count as f64 } else { 0.0 })
    }

    /// Per particle: number of particle contacts carrying force now.
    pub fn coordination(&self) -> Vec<u32> {
        let mut z = vec![0u32; self.particles.len()];
        for (i, j, _) in self.touching() {
            z[i] += 1;
            z[j] += 1;
        }
        z
    }

    /// The largest reach of any interaction [m].
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// A 64-bit FNV-1a digest of the bits of every position, velocity, angular velocity and force of
    /// the last step: two runs that print the same digest stepped to the same bits (the bench prints
    /// it, so a faster build, another thread count or the Windows build can be compared to the bit).
    pub fn state_digest(&self) -> u64 {
        let p = &self.particles;
        let (force, torque) = (self.total.forces(), self.total.torques());
        let vectors = p.position.iter().chain(&p.velocity).chain(&p.angular_velocity).chain(&force).chain(&torque);
        let words = vectors.flat_map(|v| [v.x, v.y, v.z]).chain(self.total.load.iter().map(|l| l.rolling));
        words.fold(0xcbf2_9ce4_8422_2325u64, |h, x| {
            x.to_bits().to_le_bytes().iter().fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
        })
    }
}

/// `s` cut at `cuts` (the first 0, the last `s.len()`, none decreasing): `cuts.len() - 1` slices.
pub(super) fn split_at_cuts<'a, T>(mut s: &'a mut [T], cuts: &[usize]) -> Vec<&'a mut [T]> {
    let mut out = Vec::with_capacity(cuts.len().saturating_sub(1));
    for w in cuts.windows(2) {
        let (mine, rest) = std::mem::take(&mut s).split_at_mut(w[1] - w[0]);
        out.push(mine);
        s = rest;
    }
    out
}

/// One kick: gravity, the half step h, how many half kicks (1, or 2 joined), the drift's dt (0: none).
#[derive(Clone, Copy)]
struct Kick {
    g: Vec3,
    h: f64,
    halves: usize,
    dt: f64,
}

/// What the kick reads of each sphere; `held` empty when none is held.
#[derive(Clone, Copy)]
struct Body<'a> {
    inv_mass: &'a [f64],
    inv_inertia: &'a [f64],
    radius: &'a [f64],
    held: &'a [bool],
}

/// The positions the kick measures displacements from: the last list build's, and the last near list
/// build's (empty when the near list is not valid: its displacement is then infinite).
#[derive(Clone, Copy)]
struct References<'a> {
    list: &'a [Vec3],
    near: &'a [Vec3],
}

impl<'a> References<'a> {
    /// The references of spheres [base, end), None where a list was built for fewer spheres.
    fn range(&self, base: usize, end: usize) -> (Option<&'a [Vec3]>, Option<&'a [Vec3]>) {
        (self.list.get(base..end), self.near.get(base..end))
    }
}

/// `kick_body` with the engine's instruction set; with `records` (one per sphere of the range, else
/// empty) it also writes the spheres' records after the drift (`lanes::record`).
#[allow(clippy::too_many_arguments)]
fn kick_range(
    isa: Isa,
    base: usize,
    v: &mut [Vec3],
    w: &mut [Vec3],
    x: &mut [Vec3],
    body: Body,
    load: &[Load],
    refs: References,
    kick: Kick,
    records: &mut [lanes::record::Record],
) -> (f64, f64) {
    let n = v.len();
    assert!(records.is_empty() || records.len() == n, "one record per sphere of the range");
    #[cfg(target_arch = "x86_64")]
    if isa != Isa::Baseline {
        let end = base + n;
        if body.held.is_empty() && refs.list.len() >= end {
            // Four spheres at a time on lanes, the last 0-3 one at a time (the same bits: `lanes::kick`).
            // SAFETY: an engine takes Isa::Avx2 or Isa::Avx512 (which includes AVX2) only where the CPU reports it (`Engine::set_isa`).
            let moved = unsafe { lanes::kick4(base, v, w, x, body, load, refs, kick, records) };
            let done = n / 4 * 4;
            // SAFETY: as above.
            let rest = unsafe { kick_avx2(base + done, &mut v[done..], &mut w[done..], &mut x[done..], body, load, refs, kick) };
            if !records.is_empty() {
                pack_range(base + done, &v[done..], &w[done..], &x[done..], body, &mut records[done..]);
            }
            return (moved.0.max(rest.0), moved.1.max(rest.1));
        }
        // SAFETY: an engine takes Isa::Avx2 or Isa::Avx512 (which includes AVX2) only where the CPU reports it (`Engine::set_isa`).
        let moved = unsafe { kick_avx2(base, v, w, x, body, load, refs, kick) };
        pack_range(base, v, w, x, body, records);
        return moved;
    }
    let moved = kick_body(base, v, w, x, body, load, refs, kick);
    pack_range(base, v, w, x, body, records);
    moved
}

/// The records of the spheres from `base` on (as many as `records` holds; none when it is empty).
fn pack_range(base: usize, v: &[Vec3], w: &[Vec3], x: &[Vec3], body: Body, records: &mut [lanes::record::Record]) {
    let end = base + records.len();
    lanes::record::pack(x, v, w, &body.radius[base..end], records);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn kick_avx2(
    base: usize,
    v: &mut [Vec3],
    w: &mut [Vec3],
    x: &mut [Vec3],
    body: Body,
    load: &[Load],
    refs: References,
    kick: Kick,
) -> (f64, f64) {
    kick_body(base, v, w, x, body, load, refs, kick)
}

/// Half a kick of the particles from `base` on (their slices), and the drift x += v dt (dt = 0: none).
/// Returns the largest squared displacements from the references (`References`).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn kick_body(base: usize, v: &mut [Vec3], w: &mut [Vec3], x: &mut [Vec3], body: Body, load: &[Load], refs: References, kick: Kick) -> (f64, f64) {
    let Kick { g, h, halves, dt } = kick;
    let n = v.len();
    let end = base + n;
    let (w, x, load) = (&mut w[..n], &mut x[..n], &load[base..end]);
    let (im, ii, r) = (&body.inv_mass[base..end], &body.inv_inertia[base..end], &body.radius[base..end]);
    let held = if body.held.is_empty() { None } else { Some(&body.held[base..end]) };
    // A list built for fewer spheres than there are: rebuild (infinitely far).
    let (reference, near) = refs.range(base, end);
    let (mut moved, mut moved_near): (f64, f64) = (0.0, 0.0);
    for q in 0..n {
        if held.is_some_and(|held| held[q]) {
            continue;
        }
        let l = &load[q];
        for _ in 0..halves {
            // Component by component, as nalgebra's (F m^-1 + g) h would round.
            v[q].x += (l.force.x * im[q] + g.x) * h;
            v[q].y += (l.force.y * im[q] + g.y) * h;
            v[q].z += (l.force.z * im[q] + g.z) * h;
            w[q].x += l.torque.x * ii[q] * h;
            w[q].y += l.torque.y * ii[q] * h;
            w[q].z += l.torque.z * ii[q] * h;
            // Constant directional rolling torque mu_r |f_n| R against the spin, limited so that it stops
            // the spin but never reverses it within a step.
            if l.rolling > 0.0 {
                let spin = w[q].norm();
                let brake = l.rolling * r[q] * ii[q] * h;
                let keep = if spin > brake { 1.0 - brake / spin } else { 0.0 };
                w[q] *= keep;
            }
        }
        if dt != 0.0 {
            x[q].x += v[q].x * dt;
            x[q].y += v[q].y * dt;
            x[q].z += v[q].z * dt;
            let from = |x0: Option<&[Vec3]>| match x0 {
                Some(x0) => super::dot(super::sub(x[q], x0[q]), super::sub(x[q], x0[q])),
                None => f64::INFINITY,
            };
            moved = moved.max(from(reference));
            moved_near = moved_near.max(from(near));
        }
    }
    (moved, moved_near)
}

/// The near shell for a skin and a forgetting distance [m] (`near`): a fifth of the smaller. Measured on
/// the LAMMPS bench bed and the shipped quarter (issue 30's nineteenth round, docs/benchmarks.md).
fn near_shell(skin: f64, forget: f64) -> f64 {
    0.2 * skin.min(forget)
}

/// Both the skin and the forgetting distance must exceed the adhesive necks' reach: the list must hold
/// every pair a neck still pulls, and a neck that still pulls must not forget.
fn beyond_reach(whose: &str, reach: f64, skin: f64, forget: f64) -> Result<(), String> {
    if !(skin > reach) {
        return Err(format!(
            "skin = {skin:e} m must exceed {whose} adhesive necks' reach, {reach:e} m (the largest separation at which a contact still pulls)"
        ));
    }
    if !(forget > reach) {
        return Err(format!(
            "forgetting_distance = {forget:e} m must exceed {whose} adhesive necks' reach, {reach:e} m (the largest separation at which a contact still pulls)"
        ));
    }
    Ok(())
}
