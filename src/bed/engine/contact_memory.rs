//! What a contact remembers from one step to the next, one entry per list slot or wall contact: the
//! normal law's history, the tangential spring, and the contact radius of the last step (the JKR laws'
//! starting guess; 0 where there is none). Kept as three arrays (the force loop and the lanes read each
//! on its own), handled as one: what is pushed, inserted, reset or saved is always the whole entry.

use super::super::{Vec3, ZERO};

#[derive(Debug, Clone, PartialEq)]
pub struct ContactMemory<H> {
    /// The normal law's history of each contact.
    pub history: Vec<H>,
    /// The tangential spring of each contact [N].
    pub spring: Vec<Vec3>,
    /// The contact radius of the last step [m], 0 if none.
    pub contact_radius: Vec<f64>,
}

impl<H> ContactMemory<H> {
    /// No contacts.
    pub fn new() -> ContactMemory<H> {
        ContactMemory { history: vec![], spring: vec![], contact_radius: vec![] }
    }
}

impl<H> Default for ContactMemory<H> {
    fn default() -> ContactMemory<H> {
        ContactMemory::new()
    }
}

impl<H: Copy + PartialEq> ContactMemory<H> {
    pub fn with_capacity(n: usize) -> ContactMemory<H> {
        ContactMemory { history: Vec::with_capacity(n), spring: Vec::with_capacity(n), contact_radius: Vec::with_capacity(n) }
    }

    pub fn len(&self) -> usize {
        self.history.len()
    }

    pub fn is_empty(&self) -> bool {
        self.history.is_empty()
    }

    /// Contact `k`: history, spring, contact radius.
    pub fn get(&self, k: usize) -> (H, Vec3, f64) {
        (self.history[k], self.spring[k], self.contact_radius[k])
    }

    pub fn set(&mut self, k: usize, (history, spring, contact_radius): (H, Vec3, f64)) {
        self.history[k] = history;
        self.spring[k] = spring;
        self.contact_radius[k] = contact_radius;
    }

    pub fn push(&mut self, (history, spring, contact_radius): (H, Vec3, f64)) {
        self.history.push(history);
        self.spring.push(spring);
        self.contact_radius.push(contact_radius);
    }

    /// A contact that has never touched: its interaction's initial history, no spring, no radius.
    pub fn push_fresh(&mut self, initial: H) {
        self.push((initial, ZERO, 0.0));
    }

    pub fn insert_fresh(&mut self, k: usize, initial: H) {
        self.history.insert(k, initial);
        self.spring.insert(k, ZERO);
        self.contact_radius.insert(k, 0.0);
    }

    /// Grows (or cuts) to `n` contacts, new ones fresh.
    pub fn resize_fresh(&mut self, n: usize, initial: H) {
        self.history.resize(n, initial);
        self.spring.resize(n, ZERO);
        self.contact_radius.resize(n, 0.0);
    }

    /// Contact `k` forgets (as one that has never touched).
    pub fn reset(&mut self, k: usize, initial: H) {
        self.set(k, (initial, ZERO, 0.0));
    }

    /// Whether contact `k` remembers anything beyond a fresh contact's state.
    pub fn remembers(&self, k: usize, initial: H) -> bool {
        self.history[k] != initial || self.spring[k] != ZERO || self.contact_radius[k] != 0.0
    }

    /// Bytes reserved by the three arrays.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.history.capacity() * size_of::<H>() + self.spring.capacity() * size_of::<Vec3>() + self.contact_radius.capacity() * size_of::<f64>()
    }
}
