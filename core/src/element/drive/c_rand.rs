//! The C library's `rand()` as GNU libc computes it, for MBDyn's `random` drive caller
//! (drive_.cc, `RandDriveCaller`: "Generates pseudo-random numbers using the rand(3)
//! call", input manual §Random drive): with the same seed romdyn draws MBDyn's numbers.
//!
//! glibc's `rand` is `random` with its default state of 31 words (`TYPE_3`, an additive
//! feedback generator `o_k = o_{k−31} + o_{k−3} mod 2³²`, returning `o_k >> 1`): `srand(s)`
//! fills the 31 words by the multiplicative congruential generator `16807 w mod (2³¹ − 1)`
//! from `w = s` (`s = 0` is taken as 1; the arithmetic on 32-bit signed words), then
//! discards 310 outputs. This module follows that published algorithm; its numbers are
//! checked against glibc's in the tests below.

use std::collections::HashMap;
use std::sync::Mutex;

/// `RAND_MAX` of glibc.
pub const RAND_MAX: u32 = 2_147_483_647;

/// One `srand`/`rand` stream.
#[derive(Clone, Debug, PartialEq)]
pub struct CRand {
    words: [u32; 31],
    front: usize,
    rear: usize,
}

impl CRand {
    /// The state after `srand(seed)`.
    pub fn new(seed: u32) -> Self {
        let seed = if seed == 0 { 1 } else { seed };
        let mut words = [0u32; 31];
        words[0] = seed;
        let mut word = seed as i32;
        for w in words.iter_mut().skip(1) {
            // word = 16807 word mod (2³¹ − 1), without overflow (Schrage), on signed words.
            let (hi, lo) = (i64::from(word) / 127_773, i64::from(word) % 127_773);
            let mut next = 16_807 * lo - 2_836 * hi;
            if next < 0 {
                next += 2_147_483_647;
            }
            word = next as i32;
            *w = word as u32;
        }
        let mut r = CRand { words, front: 3, rear: 0 };
        for _ in 0..310 {
            r.next_rand();
        }
        r
    }

    /// The next `rand()`, in `[0, RAND_MAX]`.
    pub fn next_rand(&mut self) -> u32 {
        let v = self.words[self.front].wrapping_add(self.words[self.rear]);
        self.words[self.front] = v;
        self.front = (self.front + 1) % 31;
        self.rear = (self.rear + 1) % 31;
        v >> 1
    }
}

/// The `rand()` numbers the `random` drive callers of one model draw (drive_.cc,
/// `RandDriveCaller`; drive.h, `DriveHandler::MyRand::Set`), in MBDyn's order: the
/// generator is seeded with the time when the model is read (`srand(time(NULL))`, drive.cc),
/// and `seed, S` (`seed, time`) seeds it again where the drive is read; each drive draws two
/// numbers when it is created (its base and its first value; a drive caller card used by
/// `reference` is created again, MBDyn's `pCopy`), and at every step number that is a
/// multiple of its `steps` each drive draws one, in the order they were created. Its value
/// is `(base + last draw) mod RAND_MAX`. The draws are numbered once for all, so a value
/// depends only on the drive and the step number: a retried step draws nothing new.
#[derive(Debug)]
pub struct RandomDraws(Mutex<Draws>);

#[derive(Debug)]
struct Draws {
    /// The seed when the model is read.
    start: u32,
    /// The drives: the place they were read at (statement, order of creation), the seed
    /// they set, if any, and their `steps`.
    drives: Vec<((usize, usize), Option<u32>, usize)>,
    /// The numbering of the draws, for that many drives.
    plan: Option<(usize, Plan)>,
    /// Sequences drawn so far, by seed.
    sequences: HashMap<u32, (CRand, Vec<u32>)>,
}

#[derive(Debug, Default)]
struct Plan {
    /// Per drive (in the order of `drives`): the seed and index of its base and first value,
    /// its place in the order of creation.
    created: Vec<(u32, usize, usize)>,
    /// The steps of the drives in the order of creation.
    steps: Vec<usize>,
    /// The seed and the numbers drawn when the model is read.
    end: (u32, usize),
}

impl Default for RandomDraws {
    /// Seeded with the clock, as MBDyn's `DriveHandler`.
    fn default() -> Self {
        RandomDraws::new(time_seed())
    }
}

impl RandomDraws {
    pub fn new(start: u32) -> Self {
        RandomDraws(Mutex::new(Draws { start, drives: Vec::new(), plan: None, sequences: HashMap::new() }))
    }

    /// Registers a drive read at `place` (statement, order) that seeds the generator with
    /// `seed` first, if any, and draws every `steps` steps; gives its number.
    pub fn register(&self, place: (usize, usize), seed: Option<u32>, steps: usize) -> usize {
        let mut d = self.lock();
        d.drives.push((place, seed, steps.max(1)));
        d.drives.len() - 1
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Draws> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Drive `id`'s `(base, current draw)` at step `step` (0 before the first).
    pub fn numbers(&self, id: usize, step: usize) -> (u32, u32) {
        let mut d = self.lock();
        if d.plan.as_ref().is_none_or(|(n, _)| *n != d.drives.len()) {
            let plan = d.plan();
            d.plan = Some((d.drives.len(), plan));
        }
        let Some((_, plan)) = &d.plan else { return (0, 0) };
        let (seed, at, order) = plan.created[id];
        let n = plan.steps[order];
        let last = n * (step / n);
        let (draw_seed, draw_at) = if last == 0 {
            (seed, at + 1)
        } else {
            // Draws before step `last`, then those of the drives created before this one at it.
            let before: usize = plan.steps.iter().map(|s| (last - 1) / s).sum();
            let now = plan.steps[..order].iter().filter(|s| last.is_multiple_of(**s)).count();
            (plan.end.0, plan.end.1 + before + now)
        };
        let base = d.number(seed, at);
        (base, d.number(draw_seed, draw_at))
    }
}

impl Draws {
    fn plan(&self) -> Plan {
        let mut order: Vec<usize> = (0..self.drives.len()).collect();
        order.sort_by_key(|&i| self.drives[i].0);
        let (mut seed, mut n) = (self.start, 0);
        let mut created = vec![(0, 0, 0); self.drives.len()];
        let mut steps = Vec::with_capacity(order.len());
        for (k, &i) in order.iter().enumerate() {
            let (_, reseed, s) = self.drives[i];
            if let Some(r) = reseed {
                (seed, n) = (r, 0);
            }
            created[i] = (seed, n, k);
            n += 2;
            steps.push(s);
        }
        Plan { created, steps, end: (seed, n) }
    }

    /// The `index`-th number after `srand(seed)`.
    fn number(&mut self, seed: u32, index: usize) -> u32 {
        let (generator, seq) = self.sequences.entry(seed).or_insert_with(|| (CRand::new(seed), Vec::new()));
        while seq.len() <= index {
            seq.push(generator.next_rand());
        }
        seq[index]
    }
}

/// `time(NULL)` as `srand` takes it.
pub fn time_seed() -> u32 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_numbers_are_glibcs() {
        // GNU libc 2.x (`srand(s); rand()` five times, through Python's ctypes on this
        // machine's libc.so.6).
        let cases: [(u32, [u32; 5]); 5] = [
            (1, [1804289383, 846930886, 1681692777, 1714636915, 1957747793]),
            (0, [1804289383, 846930886, 1681692777, 1714636915, 1957747793]),
            (7, [1045618677, 1863967299, 1272579899, 461085871, 21961325]),
            (2147483648, [1336741213, 1210407648, 1447044896, 337392383, 82502902]),
            (4294967295, [254925627, 1205188300, 366127624, 1401405153, 76053476]),
        ];
        for (seed, expected) in cases {
            let mut r = CRand::new(seed);
            let got: Vec<u32> = (0..5).map(|_| r.next_rand()).collect();
            assert_eq!(got, expected, "seed {seed}");
        }
        // The 1000th number after srand(1): 1143565421.
        let mut r = CRand::new(1);
        let last = (0..1000).map(|_| r.next_rand()).last();
        assert_eq!(last, Some(1143565421));
    }

    #[test]
    fn drives_draw_in_mbdyns_order() {
        // Two drives seeded with 7 (the second without a seed of its own), steps 2 and 3:
        // creation draws r0, r1 and r2, r3; then at step 2 the first draws r4, at step 3 the
        // second r5, at step 4 the first r6, at step 6 both, r7 and r8, in that order.
        let draws = RandomDraws::new(99);
        let second = draws.register((5, 1), None, 3);
        let first = draws.register((4, 0), Some(7), 2);
        let mut g = CRand::new(7);
        let r: Vec<u32> = (0..9).map(|_| g.next_rand()).collect();
        assert_eq!(draws.numbers(first, 0), (r[0], r[1]));
        assert_eq!(draws.numbers(first, 1), (r[0], r[1]));
        assert_eq!(draws.numbers(second, 2), (r[2], r[3]));
        assert_eq!(draws.numbers(first, 2), (r[0], r[4]));
        assert_eq!(draws.numbers(second, 3), (r[2], r[5]));
        assert_eq!(draws.numbers(first, 5), (r[0], r[6]));
        assert_eq!(draws.numbers(first, 6), (r[0], r[7]));
        assert_eq!(draws.numbers(second, 7), (r[2], r[8]));
    }
}
