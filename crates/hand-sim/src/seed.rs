//! Seeded random streams: one scene seed, a named stream per model, so adding a model to a
//! scene never changes what another model draws.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The generator for stream `name` of the scene seeded with `seed`.
///
/// ```
/// use rand::Rng;
/// let a: u64 = hand_sim::seed::stream(7, "fingertip").random();
/// let b: u64 = hand_sim::seed::stream(7, "fingertip").random();
/// let c: u64 = hand_sim::seed::stream(7, "imu_pad").random();
/// assert_eq!(a, b);
/// assert_ne!(a, c);
/// ```
pub fn stream(seed: u64, name: &str) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(derive(seed, name))
}

/// A 64-bit seed for stream `name`: FNV-1a of the name mixed into `seed` by SplitMix64, so
/// nearby scene seeds and similar names still give unrelated streams.
pub fn derive(seed: u64, name: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    splitmix64(seed ^ h)
}

fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
