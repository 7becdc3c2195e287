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
    /// Particles this part writes: [lo, hi).
    lo: usize,
    hi: usize,
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
        let (lo, hi) = (self.lo, self.hi);
        self.force[lo..hi].fill([0.0; 3]);
        self.torque[lo..hi].fill([0.0; 3]);
        self.rolling[lo..hi].fill(0.0);
        if !self.dipole.is_empty() {
            self.dipole[lo..hi].fill([0.0; 9]);
        }
        self.wall_force.fill([0.0; 3]);
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
    pub wall_contacts: Vec<WallContacts<L::History>>,
    /// Wall positions at the last rebuild.
    wall_reference: Vec<Vec3>,
    /// Largest reach of any interaction [m].
    reach: f64,
    acc: Vec<Accum>,
    total: Accum,
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
    /// Per wall: first index in that wall's contact list, particles, memory.
    walls: Vec<(usize, &'a [u32], &'a mut [H], &'a mut [Vec3])>,
    acc: &'a mut Accum,
}

impl<L: BedLaw> Engine<L> {
    /// An engine over these particles and walls. `threads` >= 1; more than one starts a pool the engine
    /// owns. The skin must exceed every interaction's reach.
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
            wall_contacts: (0..n_walls).map(|_| WallContacts { particle: vec![], normal: vec![], spring: vec![] }).collect(),
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
            reach,
            acc: (0..threads).map(|_| Accum::default()).collect(),
            total: Accum::default(),
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
        if self.threads == 1 {
            &self.acc[0]
        } else {
            &self.total
        }
    }

    /// Sets the forces of the last step (a bed loaded from a file continues exactly).
    pub fn set_totals(&mut self, force: &[Vec3], torque: &[Vec3], rolling: &[f64]) {
        let t = if self.threads == 1 { &mut self.acc[0] } else { &mut self.total };
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
        let (normal, spring) = (self.normal.clone(), self.spring.clone());
        let walls: Vec<_> = self.wall_contacts.iter().map(|w| (w.normal.clone(), w.spring.clone())).collect();
        let dt = self.dt;
        self.dt = 0.0;
        self.compute_forces();
        self.dt = dt;
        self.normal = normal;
        self.spring = spring;
        for (w, (n, s)) in self.wall_contacts.iter_mut().zip(walls) {
            w.normal = n;
            w.spring = s;
        }
    }

    /// One step of velocity Verlet.
    pub fn step(&mut self) {
        let h = 0.5 * self.dt;
        self.kick(h);
        self.drift();
        // Rebuild when a particle or a wall has moved half of (skin - reach): no pair can then have
        // closed the whole margin unseen.
        let limit = 0.5 * (self.list.skin - self.reach);
        let wall_moved = self.walls.iter().zip(&self.wall_reference).any(|(w, r)| {
            let d = sub(w.position, *r);
            dot(d, d) > limit * limit
        });
        if wall_moved || self.list.stale(&self.particles.position, limit) {
            self.rebuild();
        }
        self.compute_forces();
        self.kick(h);
        self.time += self.dt;
        self.steps += 1;
    }

    /// Several steps.
    pub fn run(&mut self, steps: u64) {
        for _ in 0..steps {
            self.step();
        }
    }

    /// Half a kick: v += (F/m + g) h, w += T/I h, and rolling friction against the spin.
    fn kick(&mut self, h: f64) {
        let threads = self.threads;
        let acc = if threads == 1 { &self.acc[0] } else { &self.total };
        let p = &mut self.particles;
        let g = self.gravity;
        let chunk = p.len().div_ceil(threads).max(1);
        let work = |(k, ((v, w), ((im, ii), r))): (usize, ((&mut [Vec3], &mut [Vec3]), ((&[f64], &[f64]), &[f64])))| {
            let base = k * chunk;
            for q in 0..v.len() {
                let i = base + q;
                let f = acc.force[i];
                let t = acc.torque[i];
                for c in 0..3 {
                    v[q][c] += (f[c] * im[q] + g[c]) * h;
                    w[q][c] += t[c] * ii[q] * h;
                }
                // Constant directional rolling torque mu_r |f_n| R against the spin, limited so that it
                // stops the spin but never reverses it within a step.
                let load = acc.rolling[i];
                if load > 0.0 {
                    let spin = super::norm(w[q]);
                    let brake = load * r[q] * ii[q] * h;
                    let keep = if spin > brake { 1.0 - brake / spin } else { 0.0 };
                    w[q] = super::scale(w[q], keep);
                }
            }
        };
        let chunks: Vec<_> = p
            .velocity
            .chunks_mut(chunk)
            .zip(p.angular_velocity.chunks_mut(chunk))
            .zip(p.inv_mass.chunks(chunk).zip(p.inv_inertia.chunks(chunk)).zip(p.radius.chunks(chunk)))
            .enumerate()
            .collect();
        match &self.pool {
            Some(pool) => pool.install(|| chunks.into_par_iter().for_each(work)),
            None => chunks.into_iter().for_each(work),
        }
    }

    fn drift(&mut self) {
        let dt = self.dt;
        let p = &mut self.particles;
        for (x, v) in p.position.iter_mut().zip(&p.velocity) {
            for c in 0..3 {
                x[c] += v[c] * dt;
            }
        }
        for w in &mut self.walls {
            for c in 0..3 {
                w.position[c] += w.velocity[c] * dt;
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
        for i in 0..self.list.rows() {
            let a = self.particles.species[i] as usize;
            for k in self.list.start[i] as usize..self.list.start[i + 1] as usize {
                if from[k] == u32::MAX {
                    let b = self.particles.species[self.list.partner[k] as usize] as usize;
                    normal.push(self.pairs[a * s + b].initial);
                    spring.push([0.0; 3]);
                } else {
                    normal.push(self.normal[from[k] as usize]);
                    spring.push(self.spring[from[k] as usize]);
                }
            }
        }
        self.normal = normal;
        self.spring = spring;
        let skin = self.list.skin;
        self.wall_reference = self.walls.iter().map(|w| w.position).collect();
        for (w, wall) in self.walls.iter().enumerate() {
            let old = std::mem::replace(&mut self.wall_contacts[w], WallContacts { particle: vec![], normal: vec![], spring: vec![] });
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
                    } else {
                        new.normal.push(self.wall_pairs[w][self.particles.species[i] as usize].initial);
                        new.spring.push([0.0; 3]);
                    }
                }
            }
        }
        self.partition();
        self.resize_buffers();
    }

    /// Splits the rows into `threads` parts of about equal work (list slots plus one per row).
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
        for k in 0..t {
            let (a, b) = (self.parts[k], self.parts[k + 1]);
            let hi = (a..b).flat_map(|i| self.list.row(i).last().map(|&j| j as usize + 1)).max().unwrap_or(b).max(b);
            self.acc[k].lo = a;
            self.acc[k].hi = hi;
        }
    }

    fn resize_buffers(&mut self) {
        let n = self.particles.len();
        let w = self.walls.len();
        let d = self.record_dipoles;
        for a in &mut self.acc {
            a.resize(n, w, d);
        }
        if self.threads > 1 {
            self.total.resize(n, w, d);
            self.total.lo = 0;
            self.total.hi = n;
        } else {
            self.acc[0].lo = 0;
            self.acc[0].hi = n;
        }
    }

    /// The force loop over pairs and wall contacts, then (with threads) the ordered sum of the parts.
    pub fn compute_forces(&mut self) {
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
        let mut wall_rest: Vec<(usize, &[u32], &mut [L::History], &mut [Vec3])> = self
            .wall_contacts
            .iter_mut()
            .map(|wc| (0usize, &wc.particle[..], &mut wc.normal[..], &mut wc.spring[..]))
            .collect();
        let mut consumed = 0usize;
        for (k, acc) in self.acc.iter_mut().enumerate() {
            let (a, b) = (self.parts[k], self.parts[k + 1]);
            let end = self.list.start[b] as usize;
            let (mine, rest) = std::mem::take(&mut normal).split_at_mut(end - consumed);
            normal = rest;
            let (mine_s, rest_s) = std::mem::take(&mut spring).split_at_mut(end - consumed);
            spring = rest_s;
            let mut walls = Vec::with_capacity(wall_rest.len());
            for (first, ps, ns, ss) in wall_rest.iter_mut() {
                let cut = ps.partition_point(|&i| (i as usize) < b);
                let (p_mine, p_rest) = ps.split_at(cut);
                let (n_mine, n_rest) = std::mem::take(ns).split_at_mut(cut);
                let (s_mine, s_rest) = std::mem::take(ss).split_at_mut(cut);
                walls.push((*first, p_mine, n_mine, s_mine));
                *first += cut;
                *ps = p_rest;
                *ns = n_rest;
                *ss = s_rest;
            }
            parts.push(Part { rows: (a, b), slot0: consumed, normal: mine, spring: mine_s, walls, acc });
            consumed = end;
        }
        match &self.pool {
            Some(pool) => pool.install(|| parts.into_par_iter().for_each(|part| run_part(&shared, part))),
            None => parts.into_iter().for_each(|part| run_part(&shared, part)),
        }
        if self.threads > 1 {
            self.reduce();
        }
        let totals = if self.threads == 1 { &self.acc[0] } else { &self.total };
        for (w, wall) in self.walls.iter_mut().enumerate() {
            wall.force = totals.wall_force[w];
        }
    }

    /// total = sum of the parts' buffers, in part order, over particle ranges in parallel.
    fn reduce(&mut self) {
        let acc = &self.acc;
        let chunk = self.particles.len().div_ceil(self.threads).max(1);
        let total = &mut self.total;
        let work = |(k, ((f, tq), r)): (usize, ((&mut [Vec3], &mut [Vec3]), &mut [f64]))| {
            let base = k * chunk;
            for q in 0..f.len() {
                let i = base + q;
                let (mut sf, mut st, mut sr) = ([0.0; 3], [0.0; 3], 0.0);
                for a in acc.iter().filter(|a| i >= a.lo && i < a.hi) {
                    for c in 0..3 {
                        sf[c] += a.force[i][c];
                        st[c] += a.torque[i][c];
                    }
                    sr += a.rolling[i];
                }
                f[q] = sf;
                tq[q] = st;
                r[q] = sr;
            }
        };
        let chunks: Vec<_> = total
            .force
            .chunks_mut(chunk)
            .zip(total.torque.chunks_mut(chunk))
            .zip(total.rolling.chunks_mut(chunk))
            .enumerate()
            .collect();
        self.pool.as_ref().expect("threads > 1 have a pool").install(|| chunks.into_par_iter().for_each(work));
        // Dipoles are recorded only on measuring steps: summed here without threads.
        for i in 0..total.dipole.len() {
            let mut sd = [0.0; 9];
            for a in acc.iter().filter(|a| i >= a.lo && i < a.hi) {
                for c in 0..9 {
                    sd[c] += a.dipole[i][c];
                }
            }
            total.dipole[i] = sd;
        }
        total.wall_force.fill([0.0; 3]);
        for a in acc {
            for (w, f) in a.wall_force.iter().enumerate() {
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
            + self.wall_contacts.iter().map(|w| w.particle.capacity() * 4 + w.normal.capacity() * h + w.spring.capacity() * 24).sum::<usize>()
            + self.acc.iter().map(acc).sum::<usize>()
            + acc(&self.total)
    }

    /// Contacts carrying force now, and their mean overlap [m] (particle-particle only).
    pub fn contact_statistics(&self) -> (usize, f64) {
        let p = &self.particles;
        let mut count = 0;
        let mut sum = 0.0;
        for i in 0..self.list.rows() {
            for (k, &j) in (self.list.start[i] as usize..).zip(self.list.row(i)) {
                let j = j as usize;
                let alpha = p.radius[i] + p.radius[j] - super::norm(sub(p.position[j], p.position[i]));
                let it = &self.pairs[p.species[i] as usize * self.species + p.species[j] as usize];
                let ev = law::NormalLaw::evaluate(&it.law, alpha, &self.normal[k]);
                if ev.branch.in_contact() {
                    count += 1;
                    sum += alpha;
                }
            }
        }
        (count, if count > 0 { sum / count as f64 } else { 0.0 })
    }

    /// Per particle: number of particle and wall contacts carrying force now.
    pub fn coordination(&self) -> Vec<u32> {
        let p = &self.particles;
        let mut z = vec![0u32; p.len()];
        for i in 0..self.list.rows() {
            for (k, &j) in (self.list.start[i] as usize..).zip(self.list.row(i)) {
                let j = j as usize;
                let alpha = p.radius[i] + p.radius[j] - super::norm(sub(p.position[j], p.position[i]));
                let it = &self.pairs[p.species[i] as usize * self.species + p.species[j] as usize];
                if law::NormalLaw::evaluate(&it.law, alpha, &self.normal[k]).branch.in_contact() {
                    z[i] += 1;
                    z[j] += 1;
                }
            }
        }
        z
    }

    /// The largest reach of any interaction [m].
    pub fn reach(&self) -> f64 {
        self.reach
    }
}

/// The force loop of one part.
fn run_part<L: BedLaw>(s: &Shared<L>, part: Part<L::History>) {
    let Part { rows, slot0, normal, spring, walls, acc } = part;
    acc.clear();
    let p = s.p;
    let dipoles = !acc.dipole.is_empty();
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
            if let Some(c) = contact(it, alpha, n, v, &mut normal[slot], &mut spring[slot], s.dt) {
                for q in 0..3 {
                    acc.force[i][q] += c.force[q];
                    acc.force[j][q] -= c.force[q];
                }
                let tq = super::cross(n, c.tangential);
                for q in 0..3 {
                    acc.torque[i][q] += li * tq[q];
                    acc.torque[j][q] += lj * tq[q];
                }
                acc.rolling[i] += c.rolling_load;
                acc.rolling[j] += c.rolling_load;
                if dipoles {
                    // |x_c - x_p| n_i F_j for both particles (004 Eq. 5.1); the partner sees -n and -F.
                    for a in 0..3 {
                        for b in 0..3 {
                            acc.dipole[i][3 * a + b] += li * n[a] * c.force[b];
                            acc.dipole[j][3 * a + b] += lj * n[a] * c.force[b];
                        }
                    }
                }
            }
        }
    }
    for (w, (_, particles, normal, spring)) in walls.into_iter().enumerate() {
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
            if let Some(c) = contact(it, t.overlap, t.normal, v, &mut normal[slot], &mut spring[slot], s.dt) {
                for q in 0..3 {
                    acc.force[i][q] += c.force[q];
                    acc.wall_force[w][q] -= c.force[q];
                }
                let tq = super::cross(t.normal, c.tangential);
                for q in 0..3 {
                    acc.torque[i][q] += li * tq[q];
                }
                acc.rolling[i] += c.rolling_load;
                if dipoles {
                    for a in 0..3 {
                        for b in 0..3 {
                            acc.dipole[i][3 * a + b] += li * t.normal[a] * c.force[b];
                        }
                    }
                }
            }
        }
    }
}
