//! Arrival-of-Time behind the `hand-traits` contact-locator trait.

use crate::geometry::{AREAS, Geometry};
use crate::score::{AotError, ArrivalEvent, eq3};
use hand_traits::{Contact, ContactLocator};

/// Locates a contact on the 3 × 3 grid with eq. 3: the area of largest `Arr_n`, with the
/// normalised margin of [`crate::Scores::confidence`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AotLocator {
    geometry: Geometry,
}

impl AotLocator {
    /// A locator for `geometry`.
    pub fn new(geometry: Geometry) -> AotLocator {
        AotLocator { geometry }
    }

    /// The pad it locates on.
    pub fn geometry(&self) -> &Geometry {
        &self.geometry
    }
}

impl ContactLocator for AotLocator {
    type Input = ArrivalEvent;
    type Error = AotError;

    fn locate(&mut self, input: &ArrivalEvent) -> Result<Contact, AotError> {
        let scores = eq3(&self.geometry, input)?;
        Ok(Contact {
            region: scores.argmax() as u16,
            regions: AREAS as u16,
            confidence: scores.confidence(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locates_near_the_earliest_loudest_sensor() {
        // Sensor 2 (bottom centre, 0.5 mm from area 7's centre) first and loudest.
        let mut loc = AotLocator::default();
        let c = loc
            .locate(&ArrivalEvent {
                pressure_pa: [100.0, 2000.0, 100.0],
                arrival_us: [Some(20_000), Some(3_000), Some(20_000)],
            })
            .unwrap();
        assert_eq!((c.region, c.regions), (7, 9));
        assert!(c.confidence > 0.0 && c.confidence <= 1.0);
        let none = ArrivalEvent {
            pressure_pa: [0.0; 3],
            arrival_us: [None; 3],
        };
        assert_eq!(loc.locate(&none), Err(AotError::NoArrival));
    }
}
