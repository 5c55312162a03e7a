//! Generational slots: the storage of joints and ribbons. Removing an item
//! frees its slot for the next one added and moves the slot's generation on,
//! so a handle to the removed item (index and generation) goes stale instead
//! of reaching its successor, as bodies' handles do.

use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct Slot<T> {
    generation: u32,
    item: Option<T>,
}

impl<T> Slot<T> {
    /// Its item, if it holds one.
    pub fn item_mut(&mut self) -> Option<&mut T> {
        self.item.as_mut()
    }
}

/// Items in slots reused through a free list.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct Slots<T> {
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
}

impl<T> Default for Slots<T> {
    fn default() -> Self {
        Slots {
            slots: Vec::new(),
            free: Vec::new(),
        }
    }
}

impl<T> Slots<T> {
    /// Stores `item`; returns its slot's index and generation.
    pub fn add(&mut self, item: T) -> (u32, u32) {
        let index = match self.free.pop() {
            Some(index) => index,
            None => {
                self.slots.push(Slot {
                    generation: 0,
                    item: None,
                });
                self.slots.len() as u32 - 1
            }
        };
        let slot = &mut self.slots[index as usize];
        slot.item = Some(item);
        (index, slot.generation)
    }

    pub fn get(&self, index: u32, generation: u32) -> Option<&T> {
        let slot = self.slots.get(index as usize)?;
        (slot.generation == generation)
            .then_some(slot.item.as_ref())
            .flatten()
    }

    pub fn remove(&mut self, index: u32, generation: u32) -> Option<T> {
        let slot = self.slots.get_mut(index as usize)?;
        if slot.generation != generation {
            return None;
        }
        let item = slot.item.take()?;
        slot.generation = slot.generation.wrapping_add(1);
        self.free.push(index);
        Some(item)
    }

    /// The item in slot `index`, whatever its generation.
    pub fn slot(&self, index: u32) -> Option<&T> {
        self.slots.get(index as usize)?.item.as_ref()
    }

    /// Every slot, live or free, by index: to be cut into runs of slots.
    pub fn as_mut_slice(&mut self) -> &mut [Slot<T>] {
        &mut self.slots
    }

    /// Slots live or free: one past the largest index.
    pub fn slot_count(&self) -> usize {
        self.slots.len()
    }

    /// The item in slot `index`, whatever its generation.
    pub fn slot_mut(&mut self, index: u32) -> Option<&mut T> {
        self.slots.get_mut(index as usize)?.item.as_mut()
    }

    /// Live items in slot order, with their index and generation.
    pub fn iter(&self) -> impl Iterator<Item = (u32, u32, &T)> + '_ {
        self.slots.iter().enumerate().filter_map(|(index, slot)| {
            slot.item
                .as_ref()
                .map(|item| (index as u32, slot.generation, item))
        })
    }

    pub fn len(&self) -> usize {
        self.slots.len() - self.free.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_removed_item_leaves_its_handle_stale_and_its_slot_reused() {
        let mut slots = Slots::default();
        let (a, ga) = slots.add("a");
        let (b, gb) = slots.add("b");
        assert_eq!(slots.remove(a, ga), Some("a"));
        assert_eq!(slots.get(a, ga), None);
        let (c, gc) = slots.add("c");
        assert_eq!((c, gc), (a, ga + 1), "the freed slot, one generation on");
        assert_eq!(slots.get(a, ga), None, "the old handle does not reach c");
        assert_eq!(slots.remove(a, ga), None);
        let live: Vec<_> = slots.iter().map(|(_, _, s)| *s).collect();
        assert_eq!(live, vec!["c", "b"]);
        assert_eq!(slots.len(), 2);
        assert_eq!(slots.get(b, gb), Some(&"b"));
    }
}
