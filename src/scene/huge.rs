//! `HugeArray`: a fixed-length array of plain records on 2 MiB pages where the
//! OS offers them (Linux transparent huge pages), for tables that path
//! vertices read at random. With 4 KiB pages a random read from a table of
//! tens of megabytes misses the TLB as well as the cache, and the page walk
//! stalls about as long as the miss itself (it shows up on the software
//! prefetch that starts the read). Embree does the same for its BVH nodes.
//!
//! Contents never depend on the backing: without huge pages (another OS, an
//! mmap failure) the array lives in an ordinary `Vec`.

use std::ops::Deref;

/// Huge-page size the mapping is aligned to.
#[cfg(target_os = "linux")]
const HUGE: usize = 2 << 20;

/// A fixed-length array of `T`, on huge pages when large enough.
pub struct HugeArray<T: Copy> {
    storage: Storage<T>,
}

enum Storage<T: Copy> {
    Heap(Vec<T>),
    #[cfg(target_os = "linux")]
    Mapped {
        base: *mut libc::c_void,
        map_len: usize,
        len: usize,
    },
}

// SAFETY: the mapping is owned exclusively by the array (like a Box<[T]>),
// written only while building, then read-only.
unsafe impl<T: Copy + Send> Send for HugeArray<T> {}
// SAFETY: as above; shared access only reads.
unsafe impl<T: Copy + Sync> Sync for HugeArray<T> {}

impl<T: Copy> HugeArray<T> {
    /// The array of the `len` items of `items` (which must yield exactly `len`).
    pub fn from_exact_iter(len: usize, items: impl Iterator<Item = T>) -> Self {
        #[cfg(target_os = "linux")]
        if let Some(mut array) = Self::map(len) {
            if let Storage::Mapped { base, map_len, .. } = array.storage {
                let data = base.cast::<T>();
                let mut n = 0;
                for item in items.take(len) {
                    // SAFETY: n < len and the mapping holds len items of T
                    // (page-aligned, so aligned for T).
                    unsafe { data.add(n).write(item) };
                    n += 1;
                }
                assert_eq!(n, len, "HugeArray: the iterator yielded too few items");
                array.storage = Storage::Mapped { base, map_len, len };
                return array;
            }
        }
        let v: Vec<T> = items.take(len).collect();
        assert_eq!(
            v.len(),
            len,
            "HugeArray: the iterator yielded too few items"
        );
        HugeArray {
            storage: Storage::Heap(v),
        }
    }

    /// An empty mapping for `len` items with the huge-page hint, or None when
    /// the table is smaller than one huge page or the OS refuses.
    #[cfg(target_os = "linux")]
    fn map(len: usize) -> Option<Self> {
        let bytes = len.checked_mul(std::mem::size_of::<T>())?;
        if bytes < HUGE || std::mem::align_of::<T>() > 4096 {
            return None;
        }
        let map_len = map_len_of::<T>(len);
        // SAFETY: a fresh private anonymous mapping; nothing else refers to it.
        let base = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                map_len,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            )
        };
        if base == libc::MAP_FAILED {
            return None;
        }
        // SAFETY: [base, base + map_len) is the mapping just made. A hint:
        // failure leaves ordinary pages, which is fine.
        unsafe { libc::madvise(base, map_len, libc::MADV_HUGEPAGE) };
        Some(HugeArray {
            storage: Storage::Mapped {
                base,
                map_len,
                len: 0,
            },
        })
    }
}

/// Bytes mapped for `len` items: whole huge pages.
#[cfg(target_os = "linux")]
fn map_len_of<T>(len: usize) -> usize {
    (len * std::mem::size_of::<T>()).next_multiple_of(HUGE)
}

impl<T: Copy> Deref for HugeArray<T> {
    type Target = [T];

    fn deref(&self) -> &[T] {
        match &self.storage {
            Storage::Heap(v) => v,
            #[cfg(target_os = "linux")]
            // SAFETY: the first `len` items were written in `from_exact_iter`.
            Storage::Mapped { base, len, .. } => unsafe {
                std::slice::from_raw_parts(base.cast::<T>(), *len)
            },
        }
    }
}

impl<T: Copy> Drop for HugeArray<T> {
    fn drop(&mut self) {
        #[cfg(target_os = "linux")]
        if let Storage::Mapped { base, map_len, .. } = self.storage {
            // SAFETY: the mapping is ours and no slice of it outlives `self`.
            unsafe { libc::munmap(base, map_len) };
        }
    }
}

impl<T: Copy> Clone for HugeArray<T> {
    fn clone(&self) -> Self {
        HugeArray::from_exact_iter(self.len(), self.iter().copied())
    }
}

impl<T: Copy> Default for HugeArray<T> {
    fn default() -> Self {
        HugeArray {
            storage: Storage::Heap(Vec::new()),
        }
    }
}

impl<T: Copy + std::fmt::Debug> std::fmt::Debug for HugeArray<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HugeArray")
            .field("len", &self.len())
            .finish_non_exhaustive()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_array_holds_what_it_was_given_small_and_large() {
        for len in [0usize, 3, 1 << 20] {
            let a = HugeArray::from_exact_iter(len, (0..len as u64).map(|i| i * 3 + 1));
            assert_eq!(a.len(), len);
            assert!(a.iter().enumerate().all(|(i, &x)| x == i as u64 * 3 + 1));
            let b = a.clone();
            assert_eq!(&a[..], &b[..]);
        }
    }

    #[test]
    #[should_panic(expected = "too few items")]
    fn huge_array_rejects_a_short_iterator() {
        let _ = HugeArray::from_exact_iter(1 << 20, 0..10u64);
    }
}
