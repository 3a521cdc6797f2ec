//! A condition that must hold without a break for some time before it counts: the MX-28's
//! overload detection ("persistent load", e-manual) and the crushing of an object (creep: a brief
//! impact peak does not crush paper or foam, a sustained squeeze does).

/// Time a condition has held without a break, and whether it has tripped (latched).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Persistence {
    held_s: f64,
    tripped: bool,
}

impl Persistence {
    /// Feeds one step of `dt_s`; returns whether the condition has now held for `after_s`.
    /// Once tripped it stays tripped until [`Persistence::reset`].
    pub fn update(&mut self, condition: bool, dt_s: f64, after_s: f64) -> bool {
        self.held_s = if condition { self.held_s + dt_s } else { 0.0 };
        self.tripped |= self.held_s >= after_s;
        self.tripped
    }

    /// Whether it has tripped.
    pub fn tripped(&self) -> bool {
        self.tripped
    }

    /// Clears the timer and the latch.
    pub fn reset(&mut self) {
        *self = Persistence::default();
    }
}
