//! The partition of the force loop over threads: the rows cut into parts of about equal work, each
//! part writing its own rows straight into the totals and the partners beyond them into its spill
//! buffer, and the spills added in part order after the loop, so a run is bitwise the same for a given
//! thread count.

use super::super::interaction::BedLaw;
use super::super::{Tensor, Vec3, ZERO};
use super::Engine;

/// Forces accumulated by one part of the force loop.
#[derive(Debug, Clone, Default)]
pub struct Accum {
    pub force: Vec<Vec3>,
    pub torque: Vec<Vec3>,
    pub rolling: Vec<f64>,
    /// Per particle sum of |x_c - x_p| n_i F_j over its contacts (Bagi, 004 Eq. 5.1), when recorded.
    pub dipole: Vec<Tensor>,
    pub wall_force: Vec<Vec3>,
}

impl Accum {
    pub(super) fn resize(&mut self, n: usize, walls: usize, dipole: bool) {
        self.force.resize(n, ZERO);
        self.torque.resize(n, ZERO);
        self.rolling.resize(n, 0.0);
        self.dipole.resize(if dipole { n } else { 0 }, Tensor::zeros());
        self.wall_force.resize(walls, ZERO);
    }

    pub(super) fn clear(&mut self) {
        self.force.fill(ZERO);
        self.torque.fill(ZERO);
        self.rolling.fill(0.0);
        self.dipole.fill(Tensor::zeros());
        self.wall_force.fill(ZERO);
    }
}

/// Where one part of the force loop writes: its own rows [base, split) straight into the totals, and
/// partners beyond its rows, [split, split + spill length), into its spill buffer (j > i, so no partner
/// is below `base`). The spills are added in part order after the loop.
pub(super) struct Sink<'a> {
    pub(super) base: usize,
    pub(super) split: usize,
    pub(super) force: &'a mut [Vec3],
    pub(super) torque: &'a mut [Vec3],
    pub(super) rolling: &'a mut [f64],
    pub(super) dipole: &'a mut [Tensor],
    pub(super) spill: &'a mut Accum,
}

impl Sink<'_> {
    /// Adds one contact's share to particle `i`, seen from `i`: `n` the unit normal toward the partner,
    /// `force` and `tangential` the total and tangential force on `i`, `lever` the distance from its
    /// centre to the contact point. Torque lever n x F_t; rolling load; and, when recorded, the dipole
    /// |x_c - x_p| n F^T of 004 Eq. 5.1. The one accumulation of particle pairs and wall contacts alike.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn add_contact(&mut self, i: usize, n: Vec3, force: Vec3, tangential: Vec3, lever: f64, rolling_load: f64, dipoles: bool) {
        *self.force(i) += force;
        *self.torque(i) += n.cross(&tangential) * lever;
        *self.rolling(i) += rolling_load;
        if dipoles {
            *self.dipole(i) += (n * lever) * force.transpose();
        }
    }

    #[inline(always)]
    pub(super) fn force(&mut self, i: usize) -> &mut Vec3 {
        if i < self.split {
            &mut self.force[i - self.base]
        } else {
            &mut self.spill.force[i - self.split]
        }
    }

    #[inline(always)]
    pub(super) fn torque(&mut self, i: usize) -> &mut Vec3 {
        if i < self.split {
            &mut self.torque[i - self.base]
        } else {
            &mut self.spill.torque[i - self.split]
        }
    }

    #[inline(always)]
    pub(super) fn rolling(&mut self, i: usize) -> &mut f64 {
        if i < self.split {
            &mut self.rolling[i - self.base]
        } else {
            &mut self.spill.rolling[i - self.split]
        }
    }

    #[inline(always)]
    pub(super) fn dipole(&mut self, i: usize) -> &mut Tensor {
        if i < self.split {
            &mut self.dipole[i - self.base]
        } else {
            &mut self.spill.dipole[i - self.split]
        }
    }
}

impl<L: BedLaw> Engine<L> {
    /// Splits the rows into `threads` parts of about equal work (list slots plus one per row), and sizes
    /// each part's spill buffer for the partners beyond its rows.
    pub(crate) fn partition(&mut self) {
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

    pub(super) fn resize_buffers(&mut self) {
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

    /// Adds each part's spill to the totals, in part order, and sums the wall reactions.
    pub(super) fn add_spills(&mut self) {
        let total = &mut self.total;
        total.wall_force.fill(ZERO);
        for (k, spill) in self.spill.iter().enumerate() {
            let b = self.parts[k + 1];
            for q in 0..spill.force.len() {
                total.force[b + q] += spill.force[q];
                total.torque[b + q] += spill.torque[q];
                total.rolling[b + q] += spill.rolling[q];
            }
            for q in 0..spill.dipole.len() {
                total.dipole[b + q] += spill.dipole[q];
            }
            for (w, f) in spill.wall_force.iter().enumerate() {
                total.wall_force[w] += f;
            }
        }
    }
}
