//! Arrays of lanes on the stack that are neither zeroed nor copied whole.
//!
//! A law's scratch arrays are sized for the largest case it accepts (a Mamdani system's 16
//! sets, an RBF network's 49 nodes), and each entry is a block's lanes (128 bytes for 16
//! cases at AVX-512). Zeroed when made and copied when returned, as plain arrays are, they
//! cost W5 8 % of its time and W6 2 % (BENCHMARKS.md), where a case uses a few of their
//! entries. A [`Slots`] is written from its first entry on and read back as a slice of the
//! entries written: nothing else touches it.

use std::mem::MaybeUninit;

/// `N` entries, none written yet. (Its only field holds no length: a constant of
/// uninitialised entries and a zero length would be written by LLVM as a `memset` of the
/// whole.)
pub struct Slots<R, const N: usize>([MaybeUninit<R>; N]);

impl<R: Copy, const N: usize> Slots<R, N> {
    pub const EMPTY: Self = Self([const { MaybeUninit::uninit() }; N]);

    /// Writing starts at the first entry. (A writer, not a method taking an iterator of the
    /// values: the closures of iterator adapters are not inlined into a kernel compiled for an
    /// instruction set, whose intrinsics then become calls.)
    #[inline(always)]
    pub fn start(&mut self) -> Filling<'_, R, N> {
        Filling {
            slots: self,
            len: 0,
        }
    }
}

/// The entries of a [`Slots`] written so far.
pub struct Filling<'a, R, const N: usize> {
    slots: &'a mut Slots<R, N>,
    len: usize,
}

impl<'a, R: Copy, const N: usize> Filling<'a, R, N> {
    /// The next entry (at most `N`, or this panics).
    #[inline(always)]
    pub fn push(&mut self, value: R) {
        self.slots.0[self.len].write(value);
        self.len += 1;
    }

    /// The entries written.
    #[inline(always)]
    pub fn done(self) -> &'a mut [R] {
        // SAFETY: the first `len` entries were written by `push`, and `MaybeUninit<R>` has the
        // layout of `R`.
        unsafe { std::slice::from_raw_parts_mut(self.slots.0.as_mut_ptr().cast::<R>(), self.len) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_entries_written_read_back_in_order() {
        let mut slots = Slots::<f64, 4>::EMPTY;
        assert!(slots.start().done().is_empty());
        let mut w = slots.start();
        for v in [1.5, -2.0, 3.25] {
            w.push(v);
        }
        assert_eq!(w.done(), &[1.5, -2.0, 3.25]);
        // written again from the first entry
        let mut w = slots.start();
        w.push(7.0);
        assert_eq!(w.done(), &[7.0]);
    }

    #[test]
    #[should_panic]
    fn a_push_past_the_last_entry_panics() {
        let mut slots = Slots::<f64, 2>::EMPTY;
        let mut w = slots.start();
        for v in 0..3 {
            w.push(v as f64);
        }
    }
}
