//! Input standardisation: the mean and scale of rows, and a row standardised by them.

use tactile_nets::norm::{mean_and_scale, standardise};

#[test]
fn mean_and_scale_of_rows() {
    let (m, s) = mean_and_scale(&[[1.0, 5.0], [3.0, 5.0]]);
    assert_eq!((m, s), ([2.0, 5.0], [1.0, 1.0]));
    assert_eq!(standardise(&[4.0, 5.0], &m, &s), [2.0, 0.0]);
    let (m, s) = mean_and_scale(&[[0.0], [4.0]]);
    assert_eq!((m, s), ([2.0], [2.0]));
    assert_eq!(mean_and_scale::<2>(&[]), ([0.0; 2], [1.0; 2]));
}
