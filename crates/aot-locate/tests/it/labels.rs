//! Eq. 4 (Kim et al. 2020 §4) round trips for every contact shape of the paper's Figure 7 at
//! every position, and the uniqueness of the labels among them. The shapes are the test's
//! vocabulary (the crate holds none).

use aot_locate::{
    AverageArea, Candidates, CellSet, DECODE_TOLERANCE, LabelError, Shape, decode_among,
};

/// Figure 7's six contact shapes, read as rectangles: 1 × 1, a 2 × 2 square ("4-1"), 3 × 3,
/// 4 × 4, 3 × 4 and a 1 × 4 bar ("4-2").
const SHAPES: [Shape; 6] = [
    Shape {
        name: "1",
        rows: 1,
        cols: 1,
    },
    Shape {
        name: "4-1",
        rows: 2,
        cols: 2,
    },
    Shape {
        name: "9",
        rows: 3,
        cols: 3,
    },
    Shape {
        name: "16",
        rows: 4,
        cols: 4,
    },
    Shape {
        name: "12",
        rows: 3,
        cols: 4,
    },
    Shape {
        name: "4-2",
        rows: 1,
        cols: 4,
    },
];

/// Every placement of [`SHAPES`] and the empty set.
fn placements() -> impl Iterator<Item = CellSet> {
    std::iter::once(CellSet::EMPTY).chain(SHAPES.into_iter().flat_map(Shape::placements))
}

/// `value` decoded among [`placements`].
pub(crate) fn decode(value: f32) -> Result<Candidates, LabelError> {
    decode_among(value, DECODE_TOLERANCE, placements())
}

#[test]
fn every_placement_round_trips() {
    // Placements: 24 singles, 15 squares 2 × 2, 8 of 3 × 3, 3 of 4 × 4, 6 of 3 × 4, 12 bars
    // 1 × 4.
    let counts: Vec<usize> = SHAPES.iter().map(|s| s.placements().count()).collect();
    assert_eq!(counts, [24, 15, 8, 3, 6, 12]);
    for shape in SHAPES {
        for set in shape.placements() {
            assert_eq!(set.len(), u32::from(shape.rows) * u32::from(shape.cols));
            let label = set.average_area();
            let cands = decode(label.value()).unwrap();
            assert!(cands.as_slice().contains(&set), "{} {set:?}", shape.name);
            for c in cands.as_slice() {
                assert_eq!(c.average_area(), label);
                // Same label ⇔ same centroid (row̄ + col̄ / 10, with col̄ < 10).
                assert_eq!(c.centroid(), set.centroid());
            }
        }
    }
}

#[test]
fn ambiguous_labels_are_exactly_the_shared_centroids() {
    let all: Vec<CellSet> = placements().collect();
    let mut ambiguous = 0;
    for set in &all {
        let sharing: Vec<&CellSet> = all
            .iter()
            .filter(|o| o.average_area() == set.average_area())
            .collect();
        let cands = decode(set.average_area().value()).unwrap();
        assert_eq!(cands.as_slice().len(), sharing.len());
        assert_eq!(cands.unique().is_some(), sharing.len() == 1);
        ambiguous += usize::from(sharing.len() > 1);
    }
    // Hand count of shared centroids: each of the 8 3 × 3 squares with the single cell at its
    // centre (16 sets), each of the 3 4 × 4 squares with the 2 × 2 square at its centre
    // (6 sets), each of the 6 3 × 4 blocks with the 1 × 4 bar on its middle row (12 sets).
    assert_eq!(ambiguous, 16 + 6 + 12);
    assert_eq!(all.len(), 1 + 24 + 15 + 8 + 3 + 6 + 12);
}

#[test]
fn table2_labels() {
    // Table 2: size 1 at 1.1 and 1.5; size 0 labelled 0.
    assert_eq!(decode(1.1).unwrap().unique(), CellSet::rect(1, 1, 1, 1));
    assert_eq!(decode(1.5).unwrap().unique(), CellSet::rect(1, 5, 1, 1));
    assert_eq!(decode(0.0).unwrap().unique(), Some(CellSet::EMPTY));
    assert_eq!(AverageArea::NONE.value(), 0.0);
}
