//! A*'s open set: an exact banded priority queue over packed `(f, tie)` keys (see [`OpenSet`]).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Open-set key: `(f, tie)` packed into one integer whose order is the pop order.
///
/// `f ≥ 0`, so its IEEE-754 bits order like its value. The tie field is `!g` (as `f32` bits,
/// so larger `g` pops first) then the cell index (lower first). Every key is a deterministic
/// function of the input, so the pop sequence is too.
#[inline(always)]
pub(super) fn open_key(f: f64, g: f64, cell: u32) -> u128 {
    let tie = (u64::from(!(g as f32).to_bits()) << 32) | u64::from(cell);
    (u128::from(f.to_bits()) << 64) | u128::from(tie)
}

/// The `f` of an open-set key.
#[inline(always)]
pub(super) fn key_f(key: u128) -> f64 {
    f64::from_bits((key >> 64) as u64)
}

/// The cell index of an open-set key.
#[inline(always)]
pub(super) fn key_cell(key: u128) -> u32 {
    key as u32
}

/// Bands per unit of `f` (per `min_cost`) in the open set.
pub(super) const BANDS_PER_UNIT: f64 = 64.0;

/// Band buckets in the open set's circular window (a power of two).
pub(super) const WINDOW_BANDS: u64 = 1024;

/// The open set: an exact priority queue for A*'s nearly monotone keys.
///
/// A* with a consistent heuristic pops `f` in non-decreasing order. Keys are grouped in bands
/// of width `1 / (BANDS_PER_UNIT · min_cost)` in `f`, indexed by the coarse key
/// `⌊f · scale⌋`, which is monotone in `f`:
/// - the **current band** is sorted once, in descending order, when it becomes current, so a
///   pop is `Vec::pop`; keys pushed into it later (or below it: a rounding-level heuristic
///   inconsistency) go to a small side heap, and a pop takes the smaller of the two fronts;
/// - later bands within a window of [`WINDOW_BANDS`] are unsorted buckets in a circular array,
///   so most pushes are appends;
/// - keys beyond the window wait in an overflow heap and move into their bucket once the window
///   reaches them (each key at most once).
///
/// Every key outside the current band has a larger coarse key, hence a larger `f`, hence a
/// larger key: each pop returns the exact minimum of the remaining keys, and the search is the
/// same as with one binary heap, only faster (bands are sorted in cache, pushes are appends).
/// Cost fields far above `min_cost` only send more keys through the overflow heap.
#[derive(Debug, Clone)]
pub(super) struct OpenSet {
    /// Coarse keys per unit of `f`.
    scale: f64,
    /// Coarse key of the current band.
    current: u64,
    /// The current band's keys as of when it became current, sorted descending.
    band: Vec<u128>,
    /// Keys pushed with a coarse key ≤ `current`.
    side: BinaryHeap<Reverse<u128>>,
    /// Bucket `c % WINDOW_BANDS` holds the keys of coarse key `c`, for
    /// `current < c < current + WINDOW_BANDS`.
    buckets: Vec<Vec<u128>>,
    /// Number of keys in `buckets`.
    bucketed: usize,
    /// Keys with coarse key ≥ `current + WINDOW_BANDS` when pushed.
    overflow: BinaryHeap<Reverse<u128>>,
}

impl Default for OpenSet {
    fn default() -> Self {
        Self {
            scale: 1.0,
            current: 0,
            band: Vec::new(),
            side: BinaryHeap::new(),
            buckets: vec![Vec::new(); WINDOW_BANDS as usize],
            bucketed: 0,
            overflow: BinaryHeap::new(),
        }
    }
}

impl OpenSet {
    /// Empties the set; bands are `1 / scale` wide in `f`.
    pub(super) fn reset(&mut self, scale: f64) {
        self.band.clear();
        self.side.clear();
        if self.bucketed > 0 {
            for b in &mut self.buckets {
                b.clear();
            }
        }
        self.bucketed = 0;
        self.overflow.clear();
        self.current = 0;
        self.scale = scale;
    }

    #[inline(always)]
    fn coarse(&self, key: u128) -> u64 {
        // Saturating float→int cast; f ≥ 0.
        (key_f(key) * self.scale) as u64
    }

    #[inline(always)]
    pub(super) fn push(&mut self, key: u128) {
        let c = self.coarse(key);
        if c <= self.current {
            self.side.push(Reverse(key));
        } else if c - self.current < WINDOW_BANDS {
            self.buckets[(c % WINDOW_BANDS) as usize].push(key);
            self.bucketed += 1;
        } else {
            self.overflow.push(Reverse(key));
        }
    }

    #[inline(always)]
    pub(super) fn pop(&mut self) -> Option<u128> {
        loop {
            match (self.band.last(), self.side.peek()) {
                (Some(&b), Some(&Reverse(s))) => {
                    return if s < b {
                        self.side.pop().map(|r| r.0)
                    } else {
                        self.band.pop()
                    };
                }
                (Some(_), None) => return self.band.pop(),
                (None, Some(_)) => return self.side.pop().map(|r| r.0),
                (None, None) => {
                    if !self.next_band() {
                        return None;
                    }
                }
            }
        }
    }

    /// Makes the next non-empty band current; false if the set is empty. Called only when the
    /// current band and the side heap are empty.
    fn next_band(&mut self) -> bool {
        loop {
            if self.bucketed == 0 {
                let Some(&Reverse(key)) = self.overflow.peek() else {
                    return false;
                };
                // Jump straight to the overflow's first band (its coarse key is > current).
                self.current = self.coarse(key) - 1;
            }
            self.current += 1;
            let window_end = self.current.saturating_add(WINDOW_BANDS);
            while let Some(&Reverse(key)) = self.overflow.peek() {
                let c = self.coarse(key);
                if c >= window_end {
                    break;
                }
                self.overflow.pop();
                self.buckets[(c % WINDOW_BANDS) as usize].push(key);
                self.bucketed += 1;
            }
            let bucket = &mut self.buckets[(self.current % WINDOW_BANDS) as usize];
            if !bucket.is_empty() {
                std::mem::swap(&mut self.band, bucket);
                self.bucketed -= self.band.len();
                self.band.sort_unstable_by(|a, b| b.cmp(a));
                return true;
            }
        }
    }
}
