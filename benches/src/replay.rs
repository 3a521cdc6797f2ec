//! Recorded stage inputs, replayed in a loop: a stage benchmarked alone sees the same inputs,
//! in the same proportions, as it does inside the full cycle.

/// A recorded sequence handed out round and round.
///
/// ```
/// use handstack_benches::replay::Replay;
/// let mut r = Replay::new(vec![1, 2, 3]).expect("not empty");
/// let got: Vec<i32> = (0..5).map(|_| *r.next_item()).collect();
/// assert_eq!(got, [1, 2, 3, 1, 2]);
/// assert!(Replay::<i32>::new(Vec::new()).is_none());
/// ```
#[derive(Debug, Clone)]
pub struct Replay<T> {
    items: Vec<T>,
    at: usize,
}

impl<T> Replay<T> {
    /// A replay of `items`; `None` when there is nothing to replay.
    pub fn new(items: Vec<T>) -> Option<Self> {
        (!items.is_empty()).then_some(Replay { items, at: 0 })
    }

    /// The next item, wrapping round at the end.
    pub fn next_item(&mut self) -> &T {
        let i = self.at;
        self.at = (self.at + 1) % self.items.len();
        &self.items[i]
    }

    /// How many items one round holds.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Never true (an empty replay cannot be built); for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
}
