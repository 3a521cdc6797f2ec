//! The one root finder the quasi-static model needs: the zero of an increasing function on a
//! bracket, clamped to the bracket's ends (a joint stop, a zero tension).

/// The `x` in `[lo, hi]` where the increasing `g` crosses zero: `lo` if `g(lo) >= 0`, `hi` if
/// `g(hi) <= 0` (the bound then takes the load). Illinois false position, which converges
/// superlinearly without derivatives; a NaN `g` is treated as "too far" so the answer stays
/// finite and inside the bracket.
pub(crate) fn increasing_root(mut g: impl FnMut(f64) -> f64, lo: f64, hi: f64, tol: f64) -> f64 {
    let (mut a, mut b) = (lo, hi);
    let (mut ga, mut gb) = (g(a), g(b));
    if ga.is_nan() || ga >= 0.0 {
        return a;
    }
    if gb <= 0.0 {
        return b;
    }
    if gb.is_nan() {
        gb = 1.0;
    }
    let mut last = 0i8;
    for _ in 0..80 {
        if b - a <= tol {
            break;
        }
        let mut c = (a * gb - b * ga) / (gb - ga);
        if c.is_nan() || c <= a || c >= b {
            c = 0.5 * (a + b);
        }
        let gc = g(c);
        if gc < 0.0 {
            a = c;
            ga = gc;
            if last == -1 {
                gb *= 0.5;
            }
            last = -1;
        } else if gc > 0.0 || gc.is_nan() {
            b = c;
            gb = if gc.is_nan() { 1.0 } else { gc };
            if last == 1 {
                ga *= 0.5;
            }
            last = 1;
        } else {
            return c;
        }
    }
    0.5 * (a + b)
}

/// [`increasing_root`] started from a bracket of half-width `half_width` around `guess`
/// (widened fourfold until it holds the root or meets `lo` / `hi`): few evaluations when the
/// root moves little between quasi-static steps.
pub(crate) fn increasing_root_near(
    mut g: impl FnMut(f64) -> f64,
    guess: f64,
    half_width: f64,
    lo: f64,
    hi: f64,
    tol: f64,
) -> f64 {
    let guess = guess.clamp(lo, hi);
    let mut w = half_width.max(tol);
    let mut a = (guess - w).max(lo);
    while a > lo && g(a) > 0.0 {
        w *= 4.0;
        a = (guess - w).max(lo);
    }
    let mut b = (guess + w).min(hi);
    while b < hi && g(b) < 0.0 {
        w *= 4.0;
        b = (guess + w).min(hi);
    }
    increasing_root(g, a, b, tol)
}

#[cfg(test)]
mod tests {
    use super::{increasing_root, increasing_root_near};

    #[test]
    fn a_warm_start_finds_the_same_root() {
        let g = |x: f64| x.powi(3) - 2.0;
        for guess in [-5.0, 0.0, 1.26, 3.9] {
            let r = increasing_root_near(g, guess, 0.01, 0.0, 4.0, 1e-12);
            assert!((r - 2f64.cbrt()).abs() < 1e-9, "{guess}: {r}");
        }
        assert_eq!(
            increasing_root_near(|x| x - 9.0, 1.0, 0.1, 0.0, 4.0, 1e-9),
            4.0
        );
        assert_eq!(
            increasing_root_near(|x| x + 9.0, 3.0, 0.1, 0.0, 4.0, 1e-9),
            0.0
        );
    }

    #[test]
    fn finds_interior_roots_and_clamps_to_the_bracket() {
        let r = increasing_root(|x| x * x * x - 2.0, 0.0, 4.0, 1e-12);
        assert!((r - 2f64.cbrt()).abs() < 1e-9, "{r}");
        assert_eq!(increasing_root(|x| x + 1.0, 0.0, 1.0, 1e-9), 0.0);
        assert_eq!(increasing_root(|x| x - 5.0, 0.0, 1.0, 1e-9), 1.0);
        let r = increasing_root(
            |x| if x > 0.5 { f64::NAN } else { x - 0.25 },
            0.0,
            1.0,
            1e-9,
        );
        assert!((r - 0.25).abs() < 1e-6, "{r}");
    }
}
