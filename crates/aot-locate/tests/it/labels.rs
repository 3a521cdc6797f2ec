//! Eq. 4 (seed 000 §4) round trips for every Figure 7 shape at every position, and the
//! uniqueness of the labels among them.

use aot_locate::{AverageArea, CellSet, FIGURE7_SHAPES, decode, figure7_placements};

#[test]
fn every_figure7_placement_round_trips() {
    // Figure 7 placements: 24 singles, 15 squares 2 × 2, 8 of 3 × 3, 3 of 4 × 4, 6 of 3 × 4,
    // 12 bars 1 × 4.
    let counts: Vec<usize> = FIGURE7_SHAPES
        .iter()
        .map(|s| s.placements().count())
        .collect();
    assert_eq!(counts, [24, 15, 8, 3, 6, 12]);
    for shape in FIGURE7_SHAPES {
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
    let all: Vec<CellSet> = figure7_placements().collect();
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
