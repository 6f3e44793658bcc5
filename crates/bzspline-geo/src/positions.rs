//! Positions held in blocks that are never moved once another follows: the
//! storage of [`crate::Arcs`]. A vector of millions of positions grows by
//! copying itself into one twice its size, holding both for a moment and up
//! to half of the new one unused after; blocks are added one at a time, so
//! what is unused is at most one block's room (and the tail a block keeps
//! when an arc too long for it moves on to the next).

use geo_types::Coord;

/// Blocks' room comes in slots of `2^SHIFT` positions (1 MiB).
const SHIFT: u32 = 16;
const SLOT: usize = 1 << SHIFT;

/// Positions at addresses: an address is a block's first slot times the
/// slot's size, plus the place in the block.
#[derive(Clone, Default)]
pub(crate) struct Positions {
    blocks: Vec<Vec<Coord>>,
    /// Each block's first slot.
    first: Vec<usize>,
    /// Each slot's block.
    slots: Vec<u32>,
}

impl Positions {
    /// Room for `n` positions in one block (none for 0).
    pub(crate) fn with_capacity(n: usize) -> Self {
        let mut p = Positions::default();
        if n > 0 {
            p.open(n);
        }
        p
    }

    /// Adds a block of room for at least `room` positions, in whole slots.
    fn open(&mut self, room: usize) {
        let slots = room.div_ceil(SLOT).max(1);
        let b = u32::try_from(self.blocks.len()).expect("fewer than 2^32 blocks of a MiB");
        self.first.push(self.slots.len());
        self.slots.resize(self.slots.len() + slots, b);
        self.blocks.push(Vec::with_capacity(slots * SLOT));
    }

    /// The room of block `b`: its slots' positions.
    fn room(&self, b: usize) -> usize {
        let end = self.first.get(b + 1).copied().unwrap_or(self.slots.len());
        (end - self.first[b]) * SLOT
    }

    /// Gives the last block, which holds only positions from its `start`
    /// on, room for at least `room` positions (only it, so its slots can
    /// grow).
    fn grow_last(&mut self, room: usize) {
        let b = self.blocks.len() - 1;
        let slots = room.div_ceil(SLOT);
        let have = self.slots.len() - self.first[b];
        if slots > have {
            self.slots.resize(self.first[b] + slots, b as u32);
            let block = &mut self.blocks[b];
            block.reserve_exact(slots * SLOT - block.len());
        }
    }

    /// One past the largest address a position may have: room for a value
    /// per position, by address, in a vector this long.
    pub(crate) fn span(&self) -> usize {
        self.slots.len() << SHIFT
    }

    /// Every block's positions, each with the address of its first: every
    /// position held, and the positions an arc moved away from
    /// ([`crate::Arcs::set`]) left behind.
    pub(crate) fn blocks(&self) -> impl Iterator<Item = (usize, &[Coord])> + '_ {
        (self.blocks.iter().enumerate()).map(|(b, block)| (self.address(b, 0), &block[..]))
    }

    fn address(&self, b: usize, place: usize) -> usize {
        (self.first[b] << SHIFT) + place
    }

    /// Adds `arc`'s positions after the last, together; returns the address
    /// of the first.
    pub(crate) fn push(&mut self, arc: impl IntoIterator<Item = Coord>) -> usize {
        let mut it = arc.into_iter();
        if self.blocks.is_empty() {
            self.open(SLOT);
        }
        let mut b = self.blocks.len() - 1;
        let mut start = self.blocks[b].len();
        loop {
            let room = self.room(b);
            let block = &mut self.blocks[b];
            while block.len() < room {
                match it.next() {
                    Some(c) => block.push(c),
                    None => return self.address(b, start),
                }
            }
            let Some(c) = it.next() else {
                return self.address(b, start);
            };
            let so_far = block.len() - start;
            let want = (2 * (so_far + 1)).max(SLOT);
            if start == 0 {
                // The block holds this arc alone: it grows.
                self.grow_last(want);
            } else {
                // The arc so far moves to a block of its own, with room to
                // grow; this one keeps its tail unused.
                let moved: Vec<Coord> = self.blocks[b].drain(start..).collect();
                self.open(want);
                b = self.blocks.len() - 1;
                start = 0;
                self.blocks[b].extend_from_slice(&moved);
            }
            self.blocks[b].push(c);
        }
    }

    /// Adds `arc` after the last; returns the address of its first position.
    pub(crate) fn push_slice(&mut self, arc: &[Coord]) -> usize {
        let fits = self
            .blocks
            .len()
            .checked_sub(1)
            .is_some_and(|b| self.room(b) - self.blocks[b].len() >= arc.len());
        if !fits {
            self.open(arc.len().max(SLOT));
        }
        let b = self.blocks.len() - 1;
        let start = self.blocks[b].len();
        self.blocks[b].extend_from_slice(arc);
        self.address(b, start)
    }

    /// The `len` positions from `address`.
    #[inline]
    pub(crate) fn get(&self, address: usize, len: usize) -> &[Coord] {
        // An empty arc's address may be the end of a full block.
        if len == 0 {
            return &[];
        }
        let b = self.slots[address >> SHIFT] as usize;
        let place = address - (self.first[b] << SHIFT);
        &self.blocks[b][place..place + len]
    }

    /// The `len` positions from `address`, to change.
    #[inline]
    pub(crate) fn get_mut(&mut self, address: usize, len: usize) -> &mut [Coord] {
        if len == 0 {
            return &mut [];
        }
        let b = self.slots[address >> SHIFT] as usize;
        let place = address - (self.first[b] << SHIFT);
        &mut self.blocks[b][place..place + len]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(i: usize) -> Coord {
        Coord {
            x: i as f64,
            y: -(i as f64),
        }
    }

    /// Arcs of every length up to a few blocks, pushed from iterators and
    /// slices in turn, read back whole, and never more than a block's room
    /// beyond what they hold in all.
    #[test]
    fn arcs_across_blocks_read_back_whole() {
        let mut p = Positions::with_capacity(10);
        let mut held = Vec::new();
        let mut total = 0;
        let mut next = 0;
        for (k, len) in [0, 1, 5, SLOT - 3, 7, 3 * SLOT + 1, 2, SLOT, 9, 5 * SLOT / 2]
            .into_iter()
            .cycle()
            .take(23)
            .enumerate()
        {
            let arc: Vec<Coord> = (next..next + len).map(c).collect();
            next += len;
            total += len;
            let at = if k % 2 == 0 {
                p.push(arc.iter().copied())
            } else {
                p.push_slice(&arc)
            };
            held.push((at, arc));
        }
        for (at, arc) in &held {
            assert_eq!(p.get(*at, arc.len()), &arc[..]);
        }
        let (at, arc) = &held[3];
        p.get_mut(*at, 1)[0] = c(0);
        assert_eq!(p.get(*at, 1)[0], c(0));
        assert_eq!(p.get(*at + 1, arc.len() - 1), &arc[1..]);
        // An empty arc after a full block, and one filling a block exactly.
        let mut q = Positions::with_capacity(SLOT);
        let full: Vec<Coord> = (0..SLOT).map(c).collect();
        let at = q.push_slice(&full);
        let (e1, e2) = (q.push([]), q.push_slice(&[]));
        assert_eq!(q.get(at, SLOT), &full[..]);
        assert!(q.get(e1, 0).is_empty() && q.get_mut(e2, 0).is_empty());
        let room: usize = p.blocks.iter().map(Vec::capacity).sum();
        let used: usize = p.blocks.iter().map(Vec::len).sum();
        assert_eq!(used, total);
        // Each move leaves at most the tail of one block unused.
        assert!(room - used <= SLOT * (p.blocks.len() + 1), "{room} {used}");
    }
}
