//! The latest chunks' results, one slot per key: whoever asks for a chunk
//! first computes it while holding the slot's lock, later askers wait and
//! share it. Only the `keep` most recently asked keys are kept, so memory
//! stays bounded however far a process walks through a drive.

use std::sync::{Arc, Mutex};

/// One chunk's result, filled once.
pub(super) type Slot<V> = Arc<Mutex<Option<V>>>;

/// The most recently asked keys and their slots (the newest last).
pub(super) struct Recent<K, V> {
    keep: usize,
    slots: Mutex<Vec<(K, Slot<V>)>>,
}

impl<K: PartialEq, V> Recent<K, V> {
    /// An empty cache keeping `keep` keys.
    pub const fn new(keep: usize) -> Self {
        Recent {
            keep,
            slots: Mutex::new(Vec::new()),
        }
    }

    /// The slot of `key` (empty if new), marked most recently used.
    pub fn slot(&self, key: K) -> Slot<V> {
        let mut slots = self.slots.lock().expect("recent chunks");
        let slot = match slots.iter().position(|(k, _)| *k == key) {
            Some(i) => slots.remove(i).1,
            None => Arc::new(Mutex::new(None)),
        };
        slots.push((key, slot.clone()));
        if slots.len() > self.keep {
            slots.remove(0);
        }
        slot
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slot_is_shared_until_its_key_falls_out_of_the_latest() {
        let r: Recent<u32, u32> = Recent::new(2);
        *r.slot(1).lock().unwrap() = Some(10);
        assert_eq!(*r.slot(1).lock().unwrap(), Some(10));
        *r.slot(2).lock().unwrap() = Some(20);
        // Asking 1 again makes 2 the oldest, so 3 pushes 2 out, not 1.
        r.slot(1);
        r.slot(3);
        assert_eq!(*r.slot(1).lock().unwrap(), Some(10));
        assert_eq!(*r.slot(2).lock().unwrap(), None);
    }
}
