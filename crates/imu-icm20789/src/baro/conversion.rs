//! Raw barometer codes → pascal and °C: the vendor's three-point conversion, in floating point
//! and in exact integer arithmetic, and its inverse (used by the chip model).
//!
//! The chip's OTP holds four constants `c0…c3`. At a temperature code `T_LSB`, with
//! `t = T_LSB − 32768`, they give three look-up points (TDK reference code `init_base` /
//! `inv_invpres_process_data`, DS-000169 §10):
//!
//! ```text
//! LUT0 = 3.5·2²⁰  + c0·t²/2²⁴        ↦ 45 000 Pa
//! LUT1 = 2048·c3  + c1·t²/2²⁴        ↦ 80 000 Pa
//! LUT2 = 11.5·2²⁰ + c2·t²/2²⁴        ↦ 105 000 Pa
//! ```
//!
//! and the curve through them is `P = A + B / (C + p_LSB)`. That curve is a Möbius map, so it
//! keeps cross-ratios; the integer path uses that to evaluate `P` from the three points
//! directly as one exact fraction of `i128`s (the LUT points times 2²⁴ are integers), with no
//! rounding before the final one. The float path computes A, B, C like the vendor code, in `f64`.

use crate::error::ConversionError;

/// The three calibration pressures, pascal.
pub const CALIBRATION_PA: [i64; 3] = [45_000, 80_000, 105_000];
/// Lower look-up point at `t = 0`, LSB (3.5·2²⁰).
pub const LUT_LOWER: i64 = 7 << 19;
/// Upper look-up point at `t = 0`, LSB (11.5·2²⁰).
pub const LUT_UPPER: i64 = 23 << 19;
/// The quadratic temperature terms are scaled by `1 / 2^QUADR_SHIFT` (quadr factor 1/2²⁴).
pub const QUADR_SHIFT: u32 = 24;
/// Multiplier of the offset constant `c3` (offst factor 2048).
pub const OFFSET_FACTOR: i64 = 2048;

/// Weights of the cross-ratio formula, `P2 − P1` and `P1 − P0` divided by their greatest common
/// divisor, so that the integer numerator stays below 2¹²¹ (see [`LutPoints::pressure_milli_pa_scaled`]).
const WEIGHTS: (i128, i128) = {
    let wm = CALIBRATION_PA[2] - CALIBRATION_PA[1];
    let wn = CALIBRATION_PA[1] - CALIBRATION_PA[0];
    let (mut a, mut b) = (wm, wn);
    while b != 0 {
        let r = a % b;
        a = b;
        b = r;
    }
    ((wm / a) as i128, (wn / a) as i128)
};

/// The largest pressure code, 2²⁴ − 1: the ADC converts to 24 bits.
pub const P_LSB_MAX: u32 = (1 << 24) - 1;

/// `p_lsb` if it is a 24-bit code, else [`ConversionError::CodeOutOfRange`]: a larger one
/// cannot come from the ADC (a bus fault), and converting it would hide that.
#[inline]
pub(crate) fn check_p_lsb(p_lsb: u32) -> Result<u32, ConversionError> {
    if p_lsb > P_LSB_MAX {
        return Err(ConversionError::CodeOutOfRange {
            code: p_lsb,
            max: P_LSB_MAX,
        });
    }
    Ok(p_lsb)
}

/// One raw measurement: the 24-bit pressure code and the 16-bit temperature code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RawSample {
    /// Pressure code, 0 … 2²⁴ − 1 ([`P_LSB_MAX`]); the conversions refuse a larger one with
    /// [`ConversionError::CodeOutOfRange`].
    pub p_lsb: u32,
    /// Temperature code.
    pub t_lsb: u16,
}

/// The three look-up points at one temperature, each times 2²⁴ so that they are exact integers.
///
/// Built by [`crate::Calibration::lut_points`], which rejects degenerate point sets, so every
/// value of this type defines a conversion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LutPoints {
    scaled: [i64; 3],
}

/// The vendor's coefficients of `P = A + B / (C + p_LSB)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// A, pascal.
    pub a: f64,
    /// B, pascal · LSB.
    pub b: f64,
    /// C, LSB.
    pub c: f64,
}

impl LutPoints {
    /// The look-up points of `otp` at temperature code `t_lsb`, or
    /// [`ConversionError::DegenerateCalibration`] when no curve passes through them.
    pub(crate) fn new(otp: [i16; 4], t_lsb: u16) -> Result<Self, ConversionError> {
        let t = i64::from(t_lsb) - 32_768;
        let t2 = t * t; // ≤ 2³⁰
        let quad = |c: i16| i64::from(c) * t2; // |·| ≤ 2⁴⁵
        let scaled = [
            (LUT_LOWER << QUADR_SHIFT) + quad(otp[0]),
            ((OFFSET_FACTOR * i64::from(otp[3])) << QUADR_SHIFT) + quad(otp[1]),
            (LUT_UPPER << QUADR_SHIFT) + quad(otp[2]),
        ];
        let [x0, x1, x2] = scaled.map(i128::from);
        let (wm, wn) = WEIGHTS;
        // Zero when the three (LUT, P) points are collinear: the vendor's C has a zero denominator.
        let collinear = wm * (x1 - x0) == wn * (x2 - x1);
        if x0 == x1 || x1 == x2 || x0 == x2 || collinear {
            return Err(ConversionError::DegenerateCalibration);
        }
        Ok(LutPoints { scaled })
    }

    /// The points times 2²⁴, exact.
    pub fn scaled(&self) -> [i64; 3] {
        self.scaled
    }

    /// The points in LSB (exact in `f64`: at most 50 significant bits).
    pub fn lsb(&self) -> [f64; 3] {
        self.scaled
            .map(|s| s as f64 / (1_u64 << QUADR_SHIFT) as f64)
    }

    /// Integer path: pressure in millipascal, rounded to nearest, for a pressure code given
    /// times 2²⁴ (`p_lsb << 24` for a real code; other values reach points between codes).
    ///
    /// With `N = (x − X0)(X1 − X2)` and `M = (x − X2)(X1 − X0)` the cross-ratio gives
    /// `P = (P0·wm·M + P2·wn·N) / (wm·M + wn·N)`, `wm : wn = (P2 − P1) : (P1 − P0) = 5 : 7`.
    /// For 24-bit codes and 16-bit OTP words |M|, |N| < 1.6·2¹⁰⁰, so every product fits `i128`;
    /// the arithmetic is checked anyway and reports [`ConversionError::OutOfRange`].
    pub fn pressure_milli_pa_scaled(&self, x: i64) -> Result<i64, ConversionError> {
        let [x0, x1, x2] = self.scaled.map(i128::from);
        let x = i128::from(x);
        let (wm, wn) = WEIGHTS;
        let p0 = i128::from(CALIBRATION_PA[0]);
        let p2 = i128::from(CALIBRATION_PA[2]);
        let n = (x - x0)
            .checked_mul(x1 - x2)
            .ok_or(ConversionError::OutOfRange)?;
        let m = (x - x2)
            .checked_mul(x1 - x0)
            .ok_or(ConversionError::OutOfRange)?;
        let wide = |k: i128, v: i128| k.checked_mul(v).ok_or(ConversionError::OutOfRange);
        let num = wide(p0 * wm, m)?
            .checked_add(wide(p2 * wn, n)?)
            .ok_or(ConversionError::OutOfRange)?;
        let den = wide(wm, m)?
            .checked_add(wide(wn, n)?)
            .ok_or(ConversionError::OutOfRange)?;
        if den == 0 {
            return Err(ConversionError::Pole);
        }
        let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
        let whole = num.div_euclid(den);
        let rest = num.rem_euclid(den); // 0 ≤ rest < den < 2¹⁰⁵: rest·1000 fits
        let milli = (rest * 1000 + den / 2) / den;
        whole
            .checked_mul(1000)
            .and_then(|w| w.checked_add(milli))
            .and_then(|v| i64::try_from(v).ok())
            .ok_or(ConversionError::OutOfRange)
    }

    /// Integer path for a real 24-bit code: pressure in millipascal. A code above
    /// [`P_LSB_MAX`] is [`ConversionError::CodeOutOfRange`].
    pub fn pressure_milli_pa(&self, p_lsb: u32) -> Result<i64, ConversionError> {
        let p_lsb = check_p_lsb(p_lsb)?;
        self.pressure_milli_pa_scaled(i64::from(p_lsb) << QUADR_SHIFT)
    }

    /// Float path, step 1: the vendor's A, B, C (TDK `calculate_conversion_constants`).
    pub fn coefficients(&self) -> Result<Coefficients, ConversionError> {
        let [s0, s1, s2] = self.lsb();
        let [p0, p1, p2] = CALIBRATION_PA.map(|p| p as f64);
        let c_den = s2 * (p0 - p1) + s0 * (p1 - p2) + s1 * (p2 - p0);
        let c = (s0 * s1 * (p0 - p1) + s1 * s2 * (p1 - p2) + s2 * s0 * (p2 - p0)) / c_den;
        let a = (p0 * s0 - p1 * s1 - (p1 - p0) * c) / (s0 - s1);
        let b = (p0 - a) * (s0 + c);
        let coefficients = Coefficients { a, b, c };
        if [a, b, c].iter().all(|v| v.is_finite()) {
            Ok(coefficients)
        } else {
            // The integer check in `new` rules this out except for rounding at a knife edge.
            Err(ConversionError::DegenerateCalibration)
        }
    }
}

impl Coefficients {
    /// Float path, step 2: `P = A + B / (C + p_LSB)` in pascal; `p_lsb` may be fractional.
    pub fn pressure_pa(&self, p_lsb: f64) -> Result<f64, ConversionError> {
        let den = self.c + p_lsb;
        if den == 0.0 {
            return Err(ConversionError::Pole);
        }
        let p = self.a + self.b / den;
        if p.is_finite() {
            Ok(p)
        } else {
            Err(ConversionError::OutOfRange)
        }
    }

    /// The inverse of [`Coefficients::pressure_pa`]: the (fractional) code that converts to
    /// `pressure_pa`, `p_LSB = B / (P − A) − C`. The chip model uses it to make its codes.
    /// A NaN or infinite pressure is [`ConversionError::NotFinite`] (infinity would give the
    /// pole, `−C`).
    pub fn p_lsb_for(&self, pressure_pa: f64) -> Result<f64, ConversionError> {
        if !pressure_pa.is_finite() {
            return Err(ConversionError::NotFinite);
        }
        let den = pressure_pa - self.a;
        if den == 0.0 {
            return Err(ConversionError::Pole);
        }
        let x = self.b / den - self.c;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(ConversionError::OutOfRange)
        }
    }
}

/// Temperature in °C from the barometer's code: `−45 + 175 · T_LSB / 2¹⁶` (DS-000169 §10).
pub fn temperature_c(t_lsb: u16) -> f32 {
    -45.0 + 175.0 * f32::from(t_lsb) / 65_536.0
}

/// Integer path of [`temperature_c`]: millidegrees Celsius, rounded down.
pub fn temperature_milli_c(t_lsb: u16) -> i32 {
    -45_000 + ((175_000 * i64::from(t_lsb)) >> 16) as i32
}

/// The temperature code nearest to `celsius`, saturated to the 16-bit range (chip model).
pub fn t_lsb_for(celsius: f32) -> u16 {
    let code = libm::roundf((celsius + 45.0) * 65_536.0 / 175.0);
    code.clamp(0.0, 65_535.0) as u16
}

/// The temperature code nearest to `celsius` without saturating: NaN or infinity is
/// [`ConversionError::NotFinite`], a temperature outside the code range (about −45 … 130 °C)
/// [`ConversionError::OutOfRange`].
pub(crate) fn t_lsb_exact(celsius: f32) -> Result<u16, ConversionError> {
    if !celsius.is_finite() {
        return Err(ConversionError::NotFinite);
    }
    let code = libm::roundf((celsius + 45.0) * 65_536.0 / 175.0);
    if (0.0..=65_535.0).contains(&code) {
        Ok(code as u16)
    } else {
        Err(ConversionError::OutOfRange)
    }
}
