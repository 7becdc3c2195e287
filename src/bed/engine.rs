//! The time step of the bed: velocity Verlet (kick, drift, forces, kick; symplectic for the conservative
//! forces, as LAMMPS' `fix nve/sphere`), the Verlet list rebuilt on displacement, and the force loop
//! split over a fixed partition of the particles. Each part accumulates into its own buffer and the
//! buffers are summed in part order, so a run is bitwise the same for a given thread count.

use super::interaction::{BedLaw, Interaction};
use super::kernel::{contact, surface_velocity};
use super::neighbors::{carry, NeighborList};
use super::particles::Particles;
use super::pool::Pool;
use super::walls::Wall;
use super::{dot, sub, Vec3};
use crate::law;
use rayon::prelude::*;

/// Contacts of one wall: the particles within range (ascending) and their memory.
#[derive(Debug, Clone)]
pub struct WallContacts<H> {
    pub particle: Vec<u32>,
    pub normal: Vec<H>,
    pub spring: Vec<Vec3>,
    /// Contact radius of the last step (the JKR laws' starting guess), 0 if none.
    pub radius: Vec<f64>,
}

/// Forces accumulated by one part of the force loop.
#[derive(Debug, Clone, Default)]
pub struct Accum {
    pub force: Vec<Vec3>,
    pub torque: Vec<Vec3>,
    pub rolling: Vec<f64>,
    /// Per particle sum of |x_c - x_p| n_i F_j over its contacts (Bagi, 004 Eq. 5.1), when recorded.
    pub dipole: Vec<[f64; 9]>,
    pub wall_force: Vec<Vec3>,
}

impl Accum {
    fn resize(&mut self, n: usize, walls: usize, dipole: bool) {
        self.force.resize(n, [0.0; 3]);
        self.torque.resize(n, [0.0; 3]);
        self.rolling.resize(n, 0.0);
        self.dipole.resize(if dipole { n } else { 0 }, [0.0; 9]);
        self.wall_force.resize(walls, [0.0; 3]);
    }

    fn clear(&mut self) {
        self.force.fill([0.0; 3]);
        self.torque.fill([0.0; 3]);
        self.rolling.fill(0.0);
        self.dipole.fill([0.0; 9]);
        self.wall_force.fill([0.0; 3]);
    }
}

/// Where one part of the force loop writes: its own rows [base, split) straight into the totals, and
/// partners beyond its rows, [split, split + spill length), into its spill buffer (j > i, so no partner
/// is below `base`). The spills are added in part order after the loop.
struct Sink<'a> {
    base: usize,
    split: usize,
    force: &'a mut [Vec3],
    torque: &'a mut [Vec3],
    rolling: &'a mut [f64],
    dipole: &'a mut [[f64; 9]],
    spill: &'a mut Accum,
}

impl Sink<'_> {
    #[inline(always)]
    fn force(&mut self, i: usize) -> &mut Vec3 {
        if i < self.split {
            &mut self.force[i - self.base]
        } else {
            &mut self.spill.force[i - self.split]
        }
    }

    #[inline(always)]
    fn torque(&mut self, i: usize) -> &mut Vec3 {
        if i < self.split {
            &mut self.torque[i - self.base]
        } else {
            &mut self.spill.torque[i - self.split]
        }
    }

    #[inline(always)]
    fn rolling(&mut self, i: usize) -> &mut f64 {
        if i < self.split {
            &mut self.rolling[i - self.base]
        } else {
            &mut self.spill.rolling[i - self.split]
        }
    }

    #[inline(always)]
    fn dipole(&mut self, i: usize) -> &mut [f64; 9] {
        if i < self.split {
            &mut self.dipole[i - self.base]
        } else {
            &mut self.spill.dipole[i - self.split]
        }
    }
}

/// The DEM engine for one normal law `L` (particle-particle and particle-wall contacts both use it,
/// each pair of species and each species-wall pair with its own parameters).
pub struct Engine<L: BedLaw> {
    pub particles: Particles,
    pub walls: Vec<Wall>,
    /// Interactions of species pairs, `pairs[a * species + b]`.
    pub pairs: Vec<Interaction<L>>,
    /// Interactions of each wall with each species, `wall_pairs[w][s]`.
    pub wall_pairs: Vec<Vec<Interaction<L>>>,
    pub species: usize,
    pub gravity: Vec3,
    /// Time step [s].
    pub dt: f64,
    /// Simulated time [s] and steps taken.
    pub time: f64,
    pub steps: u64,
    pub list: NeighborList,
    /// Normal-law history and tangential spring of each list slot.
    pub normal: Vec<L::History>,
    pub spring: Vec<Vec3>,
    /// Contact radius of each slot at the last step (the JKR laws' starting guess), 0 if none.
    pub radius: Vec<f64>,
    pub wall_contacts: Vec<WallContacts<L::History>>,
    /// Wall positions at the last rebuild.
    wall_reference: Vec<Vec3>,
    /// Largest reach of any interaction [m].
    reach: f64,
    /// Forces, torques, rolling loads (and dipoles) of the last step.
    total: Accum,
    /// Each part's spill buffer (see `Sink`).
    spill: Vec<Accum>,
    /// First row of each part of the force loop (len parts + 1).
    parts: Vec<usize>,
    pool: Option<Pool>,
    threads: usize,
    record_dipoles: bool,
}

impl<L: BedLaw> std::fmt::Debug for Engine<L> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Engine({} particles, {} walls, {} threads)", self.particles.len(), self.walls.len(), self.threads)
    }
}

/// Everything the force loop reads.
struct Shared<'a, L: BedLaw> {
    p: &'a Particles,
    list: &'a NeighborList,
    pairs: &'a [Interaction<L>],
    wall_pairs: &'a [Vec<Interaction<L>>],
    walls: &'a [Wall],
    species: usize,
    dt: f64,
}

/// One part of the force loop: rows [rows.0, rows.1) and what it may write.
struct Part<'a, H> {
    rows: (usize, usize),
    slot0: usize,
    normal: &'a mut [H],
    spring: &'a mut [Vec3],
    radius: &'a mut [f64],
    /// Per wall: particles and their memory.
    walls: Vec<WallMemory<'a, H>>,
    sink: Sink<'a>,
}

/// One wall's contacts: the particle of each, and their memory (law history, tangential spring, contact radius).
type WallMemory<'a, H> = (&'a [u32], &'a mut [H], &'a mut [Vec3], &'a mut [f64]);

impl<L: BedLaw> Engine<L> {
    /// An engine over these particles and walls. `threads` >= 1; more than one starts a pool the engine
    /// owns. The skin must exceed every interaction's reach.
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
        threads: usize,
    ) -> Result<Engine<L>, String> {
        assert_eq!(pairs.len(), species * species);
        assert_eq!(wall_pairs.len(), walls.len());
        if particles.species.iter().any(|&s| s as usize >= species) {
            return Err("a particle has a species beyond the interaction table".into());
        }
        let reach = pairs.iter().chain(wall_pairs.iter().flatten()).map(|it| it.reach).fold(0.0, f64::max);
        if !(skin > reach) {
            return Err(format!(
                "skin = {skin:e} m must exceed the reach of the adhesive necks, {reach:e} m (the largest separation at which a contact still pulls)"
            ));
        }
        if !(1..=256).contains(&threads) {
            return Err(format!("threads = {threads} is out of range: allowed [1, 256]"));
        }
        let pool = if threads > 1 { Some(Pool::new(threads)?) } else { None };
        let n_walls = walls.len();
        let mut e = Engine {
            particles,
            wall_contacts: (0..n_walls).map(|_| WallContacts { particle: vec![], normal: vec![], spring: vec![], radius: vec![] }).collect(),
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
            normal: vec![],
            spring: vec![],
            radius: vec![],
            reach,
            total: Accum::default(),
            spill: (0..threads).map(|_| Accum::default()).collect(),
            parts: vec![],
            pool,
            threads,
            record_dipoles: false,
        };
        e.rebuild();
        e.compute_forces();
        Ok(e)
    }

    pub fn threads(&self) -> usize {
        self.threads
    }

    /// The forces of the last step.
    pub fn totals(&self) -> &Accum {
        &self.total
    }

    /// Sets the forces of the last step (a bed loaded from a file continues exactly).
    pub fn set_totals(&mut self, force: &[Vec3], torque: &[Vec3], rolling: &[f64]) {
        let t = &mut self.total;
        t.force.copy_from_slice(force);
        t.torque.copy_from_slice(torque);
        t.rolling.copy_from_slice(rolling);
    }

    /// Per particle sum of |x_c - x_p| n_i F_j over its contacts (Bagi, 004 Eq. 5.1) for the current
    /// state. The force loop runs once more with a zero spring increment, which reproduces the last
    /// step's forces and leaves every history as it was.
    pub fn measure_dipoles(&mut self) -> Vec<[f64; 9]> {
        self.record_dipoles = true;
        self.resize_buffers();
        self.compute_forces_without_increment();
        let dipoles = self.totals().dipole.clone();
        self.record_dipoles = false;
        self.resize_buffers();
        self.compute_forces_without_increment();
        dipoles
    }

    /// The force loop with a zero tangential increment: the forces of the current state, with every
    /// contact's memory left exactly as it is.
    pub fn compute_forces_without_increment(&mut self) {
        // The pass re-projects springs onto the tangent plane and the Coulomb limit, which moves them by
        // rounding; the memory is put back as it was so the pass leaves no trace.
        let (normal, spring, radius) = (self.normal.clone(), self.spring.clone(), self.radius.clone());
        let walls: Vec<_> = self.wall_contacts.iter().map(|w| (w.normal.clone(), w.spring.clone(), w.radius.clone())).collect();
        let dt = self.dt;
        self.dt = 0.0;
        self.compute_forces();
        self.dt = dt;
        self.normal = normal;
        self.spring = spring;
        self.radius = radius;
        for (w, (n, s, r)) in self.wall_contacts.iter_mut().zip(walls) {
            w.normal = n;
            w.spring = s;
            w.radius = r;
        }
    }

    /// Runs `f` with the engine's workers ready: every parallel loop inside it runs on the engine's own
    /// pool, in one `install` per call, so the workers do not fall asleep between the loops of a step.
    fn with_pool<R: Send>(&mut self, f: impl FnOnce(&mut Self) -> R + Send) -> R {
        match self.pool.take() {
            Some(pool) => {
                let r = pool.install(|| f(&mut *self));
                self.pool = Some(pool);
                r
            }
            None => f(self),
        }
    }

    /// One step of velocity Verlet.
    pub fn step(&mut self) {
        self.with_pool(|e| e.step_inner());
    }

    /// Several steps.
    pub fn run(&mut self, steps: u64) {
        self.with_pool(|e| {
            for _ in 0..steps {
                e.step_inner();
            }
        });
    }

    fn step_inner(&mut self) {
        let h = 0.5 * self.dt;
        // Rebuild when a particle or a wall has moved half of (skin - reach): no pair can then have
        // closed the whole margin unseen.
        let limit = 0.5 * (self.list.skin - self.reach);
        let moved = self.kick(h, true);
        self.move_walls();
        let wall_moved = self.walls.iter().zip(&self.wall_reference).any(|(w, r)| {
            let d = sub(w.position, *r);
            dot(d, d) > limit * limit
        });
        if wall_moved || moved > limit * limit || self.list.rows() != self.particles.len() {
            self.rebuild();
        }
        self.forces_inner();
        self.kick(h, false);
        self.time += self.dt;
        self.steps += 1;
    }

    /// Half a kick: v += (F/m + g) h, w += T/I h, and rolling friction against the spin; with `drift`
    /// also x += v dt. Returns the largest squared displacement since the last list build (with drift).
    fn kick(&mut self, h: f64, drift: bool) -> f64 {
        let threads = self.threads;
        let acc = &self.total;
        let p = &mut self.particles;
        let reference = self.list.reference();
        let dt = if drift { self.dt } else { 0.0 };
        let g = self.gravity;
        if threads == 1 {
            return kick_range(0, &mut p.velocity, &mut p.angular_velocity, &mut p.position, &p.inv_mass, &p.inv_inertia, &p.radius, acc, reference, g, h, dt);
        }
        let chunk = p.len().div_ceil(threads).max(1);
        let chunks: Vec<_> = p
            .velocity
            .chunks_mut(chunk)
            .zip(p.angular_velocity.chunks_mut(chunk))
            .zip(p.position.chunks_mut(chunk))
            .zip(p.inv_mass.chunks(chunk).zip(p.inv_inertia.chunks(chunk)).zip(p.radius.chunks(chunk)))
            .enumerate()
            .collect();
        chunks
            .into_par_iter()
            .map(|(k, (((v, w), x), ((im, ii), r)))| kick_range(k * chunk, v, w, x, im, ii, r, acc, reference, g, h, dt))
            .reduce(|| 0.0, f64::max)
    }

    fn move_walls(&mut self) {
        for w in &mut self.walls {
            for c in 0..3 {
                w.position[c] += w.velocity[c] * self.dt;
            }
        }
    }

    /// Rebuilds the Verlet list and the wall contact lists, carrying every contact's memory across.
    pub fn rebuild(&mut self) {
        let old_start = std::mem::take(&mut self.list.start);
        let old_partner = std::mem::take(&mut self.list.partner);
        self.list.build(&self.particles.position, &self.particles.radius);
        // For each new slot, the old slot of the same pair (or none): the pair keeps its memory; a new
        // pair starts with the initial history of its own interaction.
        let old_slots: Vec<u32> = (0..old_partner.len() as u32).collect();
        let from = carry(&old_start, &old_partner, &old_slots, &self.list, u32::MAX);
        let s = self.species;
        let mut normal = Vec::with_capacity(from.len());
        let mut spring = Vec::with_capacity(from.len());
        let mut radius = Vec::with_capacity(from.len());
        for i in 0..self.list.rows() {
            let a = self.particles.species[i] as usize;
            for k in self.list.start[i] as usize..self.list.start[i + 1] as usize {
                if from[k] == u32::MAX {
                    let b = self.particles.species[self.list.partner[k] as usize] as usize;
                    normal.push(self.pairs[a * s + b].initial);
                    spring.push([0.0; 3]);
                    radius.push(0.0);
                } else {
                    normal.push(self.normal[from[k] as usize]);
                    spring.push(self.spring[from[k] as usize]);
                    radius.push(self.radius[from[k] as usize]);
                }
            }
        }
        self.normal = normal;
        self.spring = spring;
        self.radius = radius;
        let skin = self.list.skin;
        self.wall_reference = self.walls.iter().map(|w| w.position).collect();
        for (w, wall) in self.walls.iter().enumerate() {
            let old = std::mem::replace(&mut self.wall_contacts[w], WallContacts { particle: vec![], normal: vec![], spring: vec![], radius: vec![] });
            let mut k_old = 0;
            let new = &mut self.wall_contacts[w];
            for i in 0..self.particles.len() {
                let t = wall.touch(self.particles.position[i], self.particles.radius[i]);
                if t.overlap > -skin {
                    while k_old < old.particle.len() && (old.particle[k_old] as usize) < i {
                        k_old += 1;
                    }
                    new.particle.push(i as u32);
                    if k_old < old.particle.len() && old.particle[k_old] as usize == i {
                        new.normal.push(old.normal[k_old]);
                        new.spring.push(old.spring[k_old]);
                        new.radius.push(old.radius[k_old]);
                    } else {
                        new.normal.push(self.wall_pairs[w][self.particles.species[i] as usize].initial);
                        new.spring.push([0.0; 3]);
                        new.radius.push(0.0);
                    }
                }
            }
        }
        self.partition();
        self.resize_buffers();
    }

    /// Splits the rows into `threads` parts of about equal work (list slots plus one per row), and sizes
    /// each part's spill buffer for the partners beyond its rows.
    fn partition(&mut self) {
        let n = self.particles.len();
        let t = self.threads;
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
        self.resize_buffers();
    }

    fn resize_buffers(&mut self) {
        let n = self.particles.len();
        let w = self.walls.len();
        let d = self.record_dipoles;
        self.total.resize(n, w, d);
        for k in 0..self.threads {
            let (a, b) = (self.parts[k], self.parts[k + 1]);
            let hi = (a..b).filter_map(|i| self.list.row(i).last().map(|&j| j as usize + 1)).max().unwrap_or(b).max(b);
            let spill = &mut self.spill[k];
            spill.force.clear();
            spill.torque.clear();
            spill.rolling.clear();
            spill.dipole.clear();
            spill.resize(hi - b, w, d);
        }
    }

    /// The force loop over pairs and wall contacts, then (with threads) the ordered sum of the parts.
    pub fn compute_forces(&mut self) {
        self.with_pool(|e| e.forces_inner());
    }

    fn forces_inner(&mut self) {
        let shared = Shared {
            p: &self.particles,
            list: &self.list,
            pairs: &self.pairs,
            wall_pairs: &self.wall_pairs,
            walls: &self.walls,
            species: self.species,
            dt: self.dt,
        };
        // Cut the memory into the parts' pieces.
        let mut parts: Vec<Part<L::History>> = Vec::with_capacity(self.threads);
        let mut normal: &mut [L::History] = &mut self.normal;
        let mut spring: &mut [Vec3] = &mut self.spring;
        let mut radius: &mut [f64] = &mut self.radius;
        let mut wall_rest: Vec<WallMemory<'_, L::History>> =
            self.wall_contacts.iter_mut().map(|wc| (&wc.particle[..], &mut wc.normal[..], &mut wc.spring[..], &mut wc.radius[..])).collect();
        let mut consumed = 0usize;
        let record = self.record_dipoles;
        let mut own_f: &mut [Vec3] = &mut self.total.force;
        let mut own_t: &mut [Vec3] = &mut self.total.torque;
        let mut own_r: &mut [f64] = &mut self.total.rolling;
        let mut own_d: &mut [[f64; 9]] = &mut self.total.dipole;
        for (k, spill) in self.spill.iter_mut().enumerate() {
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
            let (f, rest) = std::mem::take(&mut own_f).split_at_mut(b - a);
            own_f = rest;
            let (t, rest) = std::mem::take(&mut own_t).split_at_mut(b - a);
            own_t = rest;
            let (r, rest) = std::mem::take(&mut own_r).split_at_mut(b - a);
            own_r = rest;
            let (d, rest) = std::mem::take(&mut own_d).split_at_mut(if record { b - a } else { 0 });
            own_d = rest;
            let sink = Sink { base: a, split: b, force: f, torque: t, rolling: r, dipole: d, spill };
            parts.push(Part { rows: (a, b), slot0: consumed, normal: mine_n, spring: mine_s, radius: mine_r, walls, sink });
            consumed += take;
        }
        if self.threads > 1 {
            parts.into_par_iter().for_each(|part| run_part(&shared, part));
        } else {
            parts.into_iter().for_each(|part| run_part(&shared, part));
        }
        self.add_spills();
        for (w, wall) in self.walls.iter_mut().enumerate() {
            wall.force = self.total.wall_force[w];
        }
    }

    /// Adds each part's spill to the totals, in part order, and sums the wall reactions.
    fn add_spills(&mut self) {
        let total = &mut self.total;
        total.wall_force.fill([0.0; 3]);
        for (k, spill) in self.spill.iter().enumerate() {
            let b = self.parts[k + 1];
            for q in 0..spill.force.len() {
                for c in 0..3 {
                    total.force[b + q][c] += spill.force[q][c];
                    total.torque[b + q][c] += spill.torque[q][c];
                }
                total.rolling[b + q] += spill.rolling[q];
            }
            for q in 0..spill.dipole.len() {
                for c in 0..9 {
                    total.dipole[b + q][c] += spill.dipole[q][c];
                }
            }
            for (w, f) in spill.wall_force.iter().enumerate() {
                for c in 0..3 {
                    total.wall_force[w][c] += f[c];
                }
            }
        }
    }

    /// Bytes held by the engine's arrays (particles, list, contact memory, buffers).
    pub fn memory_bytes(&self) -> usize {
        let h = std::mem::size_of::<L::History>();
        let acc = |a: &Accum| a.force.capacity() * 48 + a.rolling.capacity() * 8 + a.dipole.capacity() * 72;
        self.particles.memory_bytes()
            + self.list.memory_bytes()
            + self.normal.capacity() * h
            + self.spring.capacity() * 24
            + self.radius.capacity() * 8
            + self.wall_contacts.iter().map(|w| w.particle.capacity() * 4 + w.normal.capacity() * h + w.spring.capacity() * 24 + w.radius.capacity() * 8).sum::<usize>()
            + self.spill.iter().map(acc).sum::<usize>()
            + acc(&self.total)
    }

    /// The particle-particle pairs in contact now: (i, j, overlap [m]).
    fn touching(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let p = &self.particles;
        (0..self.list.rows()).flat_map(move |i| {
            (self.list.start[i] as usize..).zip(self.list.row(i)).filter_map(move |(k, &j)| {
                let j = j as usize;
                let alpha = p.radius[i] + p.radius[j] - super::norm(sub(p.position[j], p.position[i]));
                let it = &self.pairs[p.species[i] as usize * self.species + p.species[j] as usize];
                law::NormalLaw::evaluate(&it.law, alpha, &self.normal[k]).branch.in_contact().then_some((i, j, alpha))
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
}

/// Half a kick of the particles from `base` on (their slices), and the drift x += v dt (dt = 0: none).
/// Returns the largest squared displacement from `reference` (the positions of the last list build).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn kick_range(
    base: usize,
    v: &mut [Vec3],
    w: &mut [Vec3],
    x: &mut [Vec3],
    im: &[f64],
    ii: &[f64],
    r: &[f64],
    acc: &Accum,
    reference: &[Vec3],
    g: Vec3,
    h: f64,
    dt: f64,
) -> f64 {
    let n = v.len();
    let (force, torque, rolling) = (&acc.force[base..base + n], &acc.torque[base..base + n], &acc.rolling[base..base + n]);
    let (w, x, im, ii, r) = (&mut w[..n], &mut x[..n], &im[..n], &ii[..n], &r[..n]);
    let mut moved: f64 = 0.0;
    for q in 0..n {
        let (f, t) = (force[q], torque[q]);
        for c in 0..3 {
            v[q][c] += (f[c] * im[q] + g[c]) * h;
            w[q][c] += t[c] * ii[q] * h;
        }
        // Constant directional rolling torque mu_r |f_n| R against the spin, limited so that it stops the
        // spin but never reverses it within a step.
        let load = rolling[q];
        if load > 0.0 {
            let spin = super::norm(w[q]);
            let brake = load * r[q] * ii[q] * h;
            let keep = if spin > brake { 1.0 - brake / spin } else { 0.0 };
            w[q] = super::scale(w[q], keep);
        }
        if dt != 0.0 {
            for c in 0..3 {
                x[q][c] += v[q][c] * dt;
            }
            if let Some(x0) = reference.get(base + q) {
                let d = sub(x[q], *x0);
                moved = moved.max(dot(d, d));
            } else {
                moved = f64::INFINITY;
            }
        }
    }
    moved
}

/// The force loop of one part.
fn run_part<L: BedLaw>(s: &Shared<L>, part: Part<L::History>) {
    let Part { rows, slot0, normal, spring, radius, walls, mut sink } = part;
    sink.force.fill([0.0; 3]);
    sink.torque.fill([0.0; 3]);
    sink.rolling.fill(0.0);
    sink.dipole.fill([0.0; 9]);
    sink.spill.clear();
    let p = s.p;
    let dipoles = !sink.dipole.is_empty();
    for i in rows.0..rows.1 {
        let xi = p.position[i];
        let vi = p.velocity[i];
        let wi = p.angular_velocity[i];
        let ri = p.radius[i];
        let table = &s.pairs[p.species[i] as usize * s.species..];
        let first = s.list.start[i] as usize;
        for (k, &j) in (first..).zip(s.list.row(i)) {
            let j = j as usize;
            let d = sub(p.position[j], xi);
            let dist2 = dot(d, d);
            let rj = p.radius[j];
            let it = &table[p.species[j] as usize];
            let slot = k - slot0;
            let range = ri + rj + it.reach;
            if dist2 >= range * range && spring[slot] == [0.0; 3] && normal[slot] == it.initial {
                continue; // apart, beyond any neck, and nothing to forget
            }
            let dist = dist2.sqrt();
            let n = super::scale(d, 1.0 / dist);
            let alpha = ri + rj - dist;
            let (li, lj) = (ri - 0.5 * alpha, rj - 0.5 * alpha);
            let v = surface_velocity(vi, wi, li, p.velocity[j], p.angular_velocity[j], lj, n);
            if let Some(c) = contact(it, alpha, n, v, &mut normal[slot], &mut spring[slot], &mut radius[slot], s.dt) {
                let tq = super::cross(n, c.tangential);
                let fi = sink.force(i);
                for q in 0..3 {
                    fi[q] += c.force[q];
                }
                let fj = sink.force(j);
                for q in 0..3 {
                    fj[q] -= c.force[q];
                }
                let t_i = sink.torque(i);
                for q in 0..3 {
                    t_i[q] += li * tq[q];
                }
                let t_j = sink.torque(j);
                for q in 0..3 {
                    t_j[q] += lj * tq[q];
                }
                *sink.rolling(i) += c.rolling_load;
                *sink.rolling(j) += c.rolling_load;
                if dipoles {
                    // |x_c - x_p| n_i F_j for both particles (004 Eq. 5.1); the partner sees -n and -F.
                    for a in 0..3 {
                        for b in 0..3 {
                            sink.dipole(i)[3 * a + b] += li * n[a] * c.force[b];
                            sink.dipole(j)[3 * a + b] += lj * n[a] * c.force[b];
                        }
                    }
                }
            }
        }
    }
    for (w, (particles, normal, spring, radius)) in walls.into_iter().enumerate() {
        let wall = &s.walls[w];
        let table = &s.wall_pairs[w];
        for (slot, &i) in particles.iter().enumerate() {
            let i = i as usize;
            let ri = p.radius[i];
            let t = wall.touch(p.position[i], ri);
            let it = &table[p.species[i] as usize];
            if t.overlap < -it.reach && spring[slot] == [0.0; 3] && normal[slot] == it.initial {
                continue;
            }
            let li = ri - 0.5 * t.overlap;
            let v = surface_velocity(p.velocity[i], p.angular_velocity[i], li, wall.velocity, [0.0; 3], 0.0, t.normal);
            if let Some(c) = contact(it, t.overlap, t.normal, v, &mut normal[slot], &mut spring[slot], &mut radius[slot], s.dt) {
                let fi = sink.force(i);
                for q in 0..3 {
                    fi[q] += c.force[q];
                }
                for q in 0..3 {
                    sink.spill.wall_force[w][q] -= c.force[q];
                }
                let tq = super::cross(t.normal, c.tangential);
                let t_i = sink.torque(i);
                for q in 0..3 {
                    t_i[q] += li * tq[q];
                }
                *sink.rolling(i) += c.rolling_load;
                if dipoles {
                    for a in 0..3 {
                        for b in 0..3 {
                            sink.dipole(i)[3 * a + b] += li * t.normal[a] * c.force[b];
                        }
                    }
                }
            }
        }
    }
}
