//! Contact memory across rebuilds of the Verlet list: a pair that stays in the list keeps its law
//! history, tangential spring and contact radius (the rows are merged in order); a new pair starts with
//! the initial history of its own interaction. A pair beyond the skin that still remembers something
//! stays in the list: it forgets only beyond the forgetting distance (`force_loop::forget`), so what a
//! contact remembers does not depend on the skin or on when the list is rebuilt. Wall contacts alike.

use super::super::interaction::BedLaw;
use super::super::neighbors::carry;
use super::super::Vec3;
use super::contact_memory::ContactMemory;
use super::Engine;

/// Contacts of one wall: the particles within range (ascending) and their memory.
#[derive(Debug, Clone)]
pub struct WallContacts<H> {
    pub particle: Vec<u32>,
    pub memory: ContactMemory<H>,
}

impl<H> WallContacts<H> {
    pub fn new() -> WallContacts<H> {
        WallContacts { particle: vec![], memory: ContactMemory::new() }
    }
}

impl<L: BedLaw> Engine<L> {
    /// The positions of the last list build: the spheres' and the walls'.
    pub fn list_reference(&self) -> (Vec<Vec3>, Vec<Vec3>) {
        (self.list.reference().to_vec(), self.wall_reference.clone())
    }

    /// Rebuilds the lists as a running engine built them at its last rebuild, from the positions of that
    /// build (`list_reference`), carrying every contact's memory across. A restored engine then has the
    /// running one's list, partition over threads and rebuild schedule: with two threads a sphere's
    /// forces are summed in part order, and a list built at the restored positions gave another
    /// partition, so another last bit. Refused (false, nothing changed) if the lengths do not match.
    pub fn rebuild_at(&mut self, reference: &[Vec3], wall_reference: &[Vec3]) -> bool {
        if reference.len() != self.particles.len() || wall_reference.len() != self.walls.len() {
            return false;
        }
        let position = std::mem::replace(&mut self.particles.position, reference.to_vec());
        let walls: Vec<Vec3> = self.walls.iter().map(|w| w.position).collect();
        for (w, &r) in self.walls.iter_mut().zip(wall_reference) {
            w.position = r;
        }
        self.rebuild();
        self.particles.position = position;
        for (w, p) in self.walls.iter_mut().zip(walls) {
            w.position = p;
        }
        true
    }

    /// Rebuilds the Verlet list and the wall contact lists, carrying every contact's memory across.
    pub fn rebuild(&mut self) {
        self.near.valid = false;
        self.near.walk = false;
        let remembering = self.remembering_pairs();
        let old_start = std::mem::take(&mut self.list.start);
        let old_partner = std::mem::take(&mut self.list.partner);
        self.list.build(&self.particles.position, &self.particles.radius);
        // The parts over threads are cut on the list the positions give, before the remembering pairs
        // are added: an engine restored from a saved state (`rebuild_at`) then cuts the same parts, and
        // with two threads the parts decide each sphere's order of summation.
        self.cut_parts();
        // Pairs that remember and are now beyond the skin stay (few when the skin is at least the
        // forgetting distance: they forget at the next force loop).
        self.list.insert_missing(remembering);
        // For each new slot, the old slot of the same pair (or none): the pair keeps its memory; a new
        // pair starts with the initial history of its own interaction.
        let old_slots: Vec<u32> = (0..old_partner.len() as u32).collect();
        let from = carry(&old_start, &old_partner, &old_slots, &self.list, u32::MAX);
        let mut memory = ContactMemory::with_capacity(from.len());
        for i in 0..self.list.rows() {
            let a = self.particles.species[i] as usize;
            for k in self.list.start[i] as usize..self.list.start[i + 1] as usize {
                if from[k] == u32::MAX {
                    let b = self.particles.species[self.list.partner[k] as usize] as usize;
                    memory.push_fresh(self.pair(a, b).initial);
                } else {
                    memory.push(self.memory.get(from[k] as usize));
                }
            }
        }
        self.memory = memory;
        let skin = self.list.skin;
        self.wall_reference = self.walls.iter().map(|w| w.position).collect();
        for (w, wall) in self.walls.iter().enumerate() {
            let old = std::mem::replace(&mut self.wall_contacts[w], WallContacts::new());
            let mut k_old = 0;
            let new = &mut self.wall_contacts[w];
            for i in 0..self.particles.len() {
                let t = wall.touch(self.particles.position[i], self.particles.radius[i]);
                while k_old < old.particle.len() && (old.particle[k_old] as usize) < i {
                    k_old += 1;
                }
                let initial = self.wall_pairs[w][self.particles.species[i] as usize].initial;
                let had = k_old < old.particle.len() && old.particle[k_old] as usize == i;
                // Within the skin, or beyond it and still remembering (as the pairs).
                if t.overlap > -skin || (had && old.memory.remembers(k_old, initial)) {
                    new.particle.push(i as u32);
                    if had {
                        new.memory.push(old.memory.get(k_old));
                    } else {
                        new.memory.push_fresh(initial);
                    }
                }
            }
        }
        self.resize_buffers();
    }

    /// The list's contacts that remember something (`ContactMemory::remembers`): (i, j, slot).
    pub(crate) fn remembering(&self) -> impl Iterator<Item = (usize, u32, usize)> + '_ {
        let sp = &self.particles.species;
        (0..self.list.rows()).flat_map(move |i| {
            (self.list.start[i] as usize..)
                .zip(self.list.row(i))
                .filter_map(move |(k, &j)| self.memory.remembers(k, self.pair(sp[i] as usize, sp[j as usize] as usize).initial).then_some((i, j, k)))
        })
    }

    /// The list's remembering pairs beyond half the skin, as (i, j): those the new list may lack (the
    /// nearer ones it holds). None when the particles are not the list's (a rebuild after spheres were
    /// added).
    fn remembering_pairs(&self) -> Vec<(u32, u32)> {
        let p = &self.particles;
        if self.list.rows() != p.len() {
            return Vec::new();
        }
        let half_skin = 0.5 * self.list.skin;
        self.remembering()
            .filter(|&(i, j, _)| {
                let j = j as usize;
                let d = super::super::sub(p.position[j], p.position[i]);
                let far = p.radius[i] + p.radius[j] + half_skin;
                super::super::dot(d, d) >= far * far
            })
            .map(|(i, j, _)| (i as u32, j))
            .collect()
    }
}
