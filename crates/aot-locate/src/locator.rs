//! Arrival-of-Time behind the `hand-traits` contact-locator trait.

use crate::geometry::{AREAS, Geometry};
use crate::ranging::Ranging;
use crate::score::{AotError, ArrivalEvent, Scores, eq3};
use hand_traits::{Contact, ContactLocator};

/// Which area scores a locator ranks.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Scorer {
    /// Kim et al. 2020's eq. 3 exactly as written ([`eq3`]).
    #[default]
    Eq3,
    /// Arrival times as ranges ([`Ranging::scores`]): translation-aware, fitted.
    Ranging(Ranging),
}

/// Locates a contact on the 3 × 3 grid of a pad's [`Geometry`]: the area of largest score
/// (eq. 3's `Arr_n` unless built [`with_scorer`](AotLocator::with_scorer)), with the
/// normalised margin of [`crate::Scores::confidence`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AotLocator {
    geometry: Geometry,
    scorer: Scorer,
}

impl AotLocator {
    /// An eq. 3 locator for `geometry`.
    pub fn new(geometry: Geometry) -> AotLocator {
        AotLocator {
            geometry,
            scorer: Scorer::Eq3,
        }
    }

    /// A locator for `geometry` ranking `scorer`'s scores.
    pub fn with_scorer(geometry: Geometry, scorer: Scorer) -> AotLocator {
        AotLocator { geometry, scorer }
    }

    /// The nine area scores for `input`.
    pub fn scores(&self, input: &ArrivalEvent) -> Result<Scores, AotError> {
        match &self.scorer {
            Scorer::Eq3 => eq3(&self.geometry, input),
            Scorer::Ranging(model) => model.scores(&self.geometry, input),
        }
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
        let scores = self.scores(input)?;
        Ok(Contact {
            region: scores.argmax() as u16,
            regions: AREAS as u16,
            confidence: scores.confidence(),
            // Eq. 3 is a formula over the arrival order, valid for any arrivals.
            in_range: true,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locates_near_the_earliest_loudest_sensor() {
        // An 18 × 12 mm pad, sensors in an inverted triangle.
        let pad = crate::AreaGrid {
            width_mm: 18.0,
            height_mm: 12.0,
        };
        let sensors = [[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]];
        // Sensor 2 (bottom centre, 0.5 mm from area 7's centre) first and loudest.
        let mut loc = AotLocator::new(Geometry::new(sensors, pad).unwrap());
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
