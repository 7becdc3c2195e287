//! Neighbour search: linked cells find the pairs closer than r_i + r_j + skin, stored as a Verlet list
//! in compressed rows (for each particle i its partners j > i, ascending). The list is rebuilt when some
//! particle has moved more than half of (skin - reach) since the last build, so no pair can come within
//! acting range unseen. Per-contact memory lives in arrays parallel to the list; `carry` moves it to the
//! new list by merging the sorted rows, so a pair that stays keeps its history and a pair that leaves the
//! list drops it.

use super::Vec3;

#[derive(Debug, Clone, Default)]
pub struct NeighborList {
    /// Row starts: the partners of i are `partner[start[i]..start[i + 1]]`.
    pub start: Vec<u32>,
    pub partner: Vec<u32>,
    /// The row of each slot (`partner[k]` is a partner of `owner[k]`), for loops over slots.
    pub owner: Vec<u32>,
    /// Positions at the last build.
    reference: Vec<Vec3>,
    /// Extra distance beyond touching kept in the list [m].
    pub skin: f64,
    /// Builds so far.
    pub builds: u64,
    cell_start: Vec<u32>,
    cell_items: Vec<u32>,
    cell_of: Vec<u32>,
}

impl NeighborList {
    pub fn new(skin: f64) -> NeighborList {
        NeighborList { skin, ..Default::default() }
    }

    pub fn rows(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    /// Partners of `i`.
    #[inline]
    pub fn row(&self, i: usize) -> &[u32] {
        &self.partner[self.start[i] as usize..self.start[i + 1] as usize]
    }

    /// Positions at the last build.
    pub fn reference(&self) -> &[Vec3] {
        &self.reference
    }

    /// Rebuilds the list for these positions and radii.
    pub fn build(&mut self, position: &[Vec3], radius: &[f64]) {
        let n = position.len();
        self.reference = position.to_vec();
        self.builds += 1;
        self.start.clear();
        self.partner.clear();
        if n == 0 {
            self.start.push(0);
            return;
        }
        let r_max = radius.iter().cloned().fold(0.0, f64::max);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for x in position {
            for c in 0..3 {
                lo[c] = lo[c].min(x[c]);
                hi[c] = hi[c].max(x[c]);
            }
        }
        // Cells at least as wide as the longest pair range; widened if particles spread so far that the
        // grid would hold many more cells than particles.
        let mut size = 2.0 * r_max + self.skin;
        let dims = |size: f64| -> [usize; 3] {
            let mut d = [1usize; 3];
            for c in 0..3 {
                d[c] = (((hi[c] - lo[c]) / size).floor() as usize + 1).max(1);
            }
            d
        };
        let mut dim = dims(size);
        while (dim[0] as f64) * (dim[1] as f64) * (dim[2] as f64) > 8.0 * n as f64 + 1000.0 {
            size *= 1.5;
            dim = dims(size);
        }
        let cell_count = dim[0] * dim[1] * dim[2];
        let coord = |x: &Vec3| -> [usize; 3] {
            let mut k = [0usize; 3];
            for c in 0..3 {
                k[c] = (((x[c] - lo[c]) / size) as usize).min(dim[c] - 1);
            }
            k
        };
        let index = |k: [usize; 3]| (k[2] * dim[1] + k[1]) * dim[0] + k[0];
        self.cell_of.clear();
        self.cell_of.extend(position.iter().map(|x| index(coord(x)) as u32));
        self.cell_start.clear();
        self.cell_start.resize(cell_count + 1, 0);
        for &c in &self.cell_of {
            self.cell_start[c as usize + 1] += 1;
        }
        for c in 0..cell_count {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        self.cell_items.clear();
        self.cell_items.resize(n, 0);
        let mut fill = self.cell_start.clone();
        for (i, &c) in self.cell_of.iter().enumerate() {
            self.cell_items[fill[c as usize] as usize] = i as u32;
            fill[c as usize] += 1;
        }
        let skin = self.skin;
        self.start.push(0);
        for i in 0..n {
            let xi = position[i];
            let ri = radius[i];
            let k = coord(&xi);
            let row_begin = self.partner.len();
            for dz in -1i64..=1 {
                let z = k[2] as i64 + dz;
                if z < 0 || z >= dim[2] as i64 {
                    continue;
                }
                for dy in -1i64..=1 {
                    let y = k[1] as i64 + dy;
                    if y < 0 || y >= dim[1] as i64 {
                        continue;
                    }
                    for dx in -1i64..=1 {
                        let x = k[0] as i64 + dx;
                        if x < 0 || x >= dim[0] as i64 {
                            continue;
                        }
                        let c = index([x as usize, y as usize, z as usize]);
                        for &j in &self.cell_items[self.cell_start[c] as usize..self.cell_start[c + 1] as usize] {
                            if (j as usize) <= i {
                                continue;
                            }
                            let range = ri + radius[j as usize] + skin;
                            if (position[j as usize] - xi).norm_squared() < range * range {
                                self.partner.push(j);
                            }
                        }
                    }
                }
            }
            self.partner[row_begin..].sort_unstable();
            self.start.push(self.partner.len() as u32);
        }
        self.fill_owner();
    }

    fn fill_owner(&mut self) {
        self.owner.clear();
        for i in 0..self.rows() {
            let len = (self.start[i + 1] - self.start[i]) as usize;
            self.owner.extend(std::iter::repeat_n(i as u32, len));
        }
    }

    /// Adds pairs (i < j) that are not in the list, keeping each row sorted: a saved contact that has
    /// moved beyond the list's range since the saving engine's last build still belongs to it until the
    /// next rebuild, and the loaded engine must hold it too to continue the same way.
    /// Adds the pairs (i < j) the list lacks; true if any was added (then slots moved).
    pub fn insert_missing(&mut self, pairs: impl IntoIterator<Item = (u32, u32)>) -> bool {
        let missing: Vec<(u32, u32)> = pairs.into_iter().filter(|&(i, j)| self.row(i as usize).binary_search(&j).is_err()).collect();
        self.insert_pairs(&missing);
        !missing.is_empty()
    }

    pub fn insert_pairs(&mut self, extra: &[(u32, u32)]) {
        if extra.is_empty() {
            return;
        }
        let rows = self.rows();
        let mut add: Vec<Vec<u32>> = vec![Vec::new(); rows];
        for &(i, j) in extra {
            add[i as usize].push(j);
        }
        let mut start = Vec::with_capacity(rows + 1);
        let mut partner = Vec::with_capacity(self.partner.len() + extra.len());
        start.push(0);
        for (i, more) in add.iter_mut().enumerate() {
            more.extend_from_slice(self.row(i));
            more.sort_unstable();
            more.dedup();
            partner.extend_from_slice(more);
            start.push(partner.len() as u32);
        }
        self.start = start;
        self.partner = partner;
        self.fill_owner();
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        (self.start.capacity()
            + self.partner.capacity()
            + self.owner.capacity()
            + self.cell_start.capacity()
            + self.cell_items.capacity()
            + self.cell_of.capacity())
            * std::mem::size_of::<u32>()
            + self.reference.capacity() * std::mem::size_of::<Vec3>()
    }
}

/// Moves per-pair data from an old list to a new one: a pair in both keeps its value, a new pair gets
/// `fresh`. Rows of both lists are sorted, so each row is one merge.
pub fn carry<T: Copy>(old_start: &[u32], old_partner: &[u32], old: &[T], new: &NeighborList, fresh: T) -> Vec<T> {
    let mut out = Vec::with_capacity(new.partner.len());
    for i in 0..new.rows() {
        let row = new.row(i);
        let (mut a, a_end) = if i + 1 < old_start.len() { (old_start[i] as usize, old_start[i + 1] as usize) } else { (0, 0) };
        for &j in row {
            while a < a_end && old_partner[a] < j {
                a += 1;
            }
            if a < a_end && old_partner[a] == j {
                out.push(old[a]);
            } else {
                out.push(fresh);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_exactly_the_pairs_within_range() {
        let mut rng = crate::bed::random::Random::new(3);
        let n = 400;
        let x: Vec<Vec3> = (0..n).map(|_| Vec3::new(rng.uniform() * 0.01, rng.uniform() * 0.01, rng.uniform() * 0.02)).collect();
        let r: Vec<f64> = (0..n).map(|_| 3e-4 + 4e-4 * rng.uniform()).collect();
        let mut list = NeighborList::new(1e-4);
        list.build(&x, &r);
        let mut brute = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let d = (x[i] - x[j]).norm();
                if d < r[i] + r[j] + 1e-4 {
                    brute.push((i as u32, j as u32));
                }
            }
        }
        let mut found = Vec::new();
        for i in 0..n {
            found.extend(list.row(i).iter().map(|&j| (i as u32, j)));
        }
        assert!(!brute.is_empty());
        assert_eq!(found, brute);
    }

    #[test]
    fn inserted_pairs_join_their_rows_in_order_and_other_rows_stay() {
        let mut a = NeighborList::new(0.0);
        // Rows 0: [2, 5], 1: [5], 2: [], 3: [].
        a.start = vec![0, 2, 3, 3, 3];
        a.partner = vec![2, 5, 5];
        // Row 1 gets 3 and a pair it has; row 2 gets 5 (as row 1's last partner: both must stay).
        a.insert_pairs(&[(1, 3), (1, 5), (2, 5), (0, 3)]);
        assert_eq!(a.row(0), &[2, 3, 5]);
        assert_eq!(a.row(1), &[3, 5]);
        assert_eq!(a.row(2), &[5]);
        assert_eq!(a.row(3), &[] as &[u32]);
    }

    #[test]
    fn carry_keeps_pairs_that_stay_and_drops_the_rest() {
        let mut a = NeighborList::new(0.0);
        a.start = vec![0, 2, 3, 3];
        a.partner = vec![1, 2, 2];
        let old = vec![10, 20, 30];
        let mut b = NeighborList::new(0.0);
        b.start = vec![0, 1, 1, 1];
        b.partner = vec![2];
        assert_eq!(carry(&a.start, &a.partner, &old, &b, 0), vec![20]);
        b.start = vec![0, 1, 2, 2];
        b.partner = vec![2, 2];
        assert_eq!(carry(&a.start, &a.partner, &old, &b, 0), vec![20, 30]);
    }
}
