//! From ADC counts to physical values: each FSR's divider voltage to newtons, each distal
//! potentiometer's wiper voltage to degrees. The underactuated-hand softness paper ("Distinguish
//! the Textures of Grasped Objects…", §3.1) calibrates both sensors so that the classifier reads
//! forces in N and angles in degrees; it publishes neither law, so the defaults here are a
//! stated model of its parts (the SF10-60 strip FSR, a 270° potentiometer, a 10-bit ADC at 5 V),
//! and a user's own hand states its own in the scene.

/// One kilogram-force, N.
pub const KGF_N: f64 = 9.806_65;

/// Codes of the Arduino's 10-bit ADC (ATmega2560 datasheet, §26.7 "ADC Conversion Result":
/// `ADC = Vin · 1024 / Vref`).
pub const ADC_CODES: u16 = 1024;

/// The voltage an ADC code stands for with reference `vref_v`: the middle of its bin
/// (`(code + ½) · Vref / 1024`), so decoding is unbiased. Codes above 1023 read as 1023.
///
/// ```
/// use underactuated_hand::calibration::adc_volts;
/// assert!((adc_volts(512, 5.0) - 2.5024).abs() < 1e-4);
/// assert_eq!(adc_volts(5000, 5.0), adc_volts(1023, 5.0));
/// ```
// The laws below run per sample, across crates (the hand, its simulator): inlined there.
#[inline]
pub fn adc_volts(code: u16, vref_v: f64) -> f64 {
    (f64::from(code.min(ADC_CODES - 1)) + 0.5) * vref_v / f64::from(ADC_CODES)
}

/// A force-sensing resistor in a voltage divider (FSR from the supply to the pin, `divider_ohm`
/// to ground), its resistance falling as a power of force: `R(F) = R₁ · (F / 1 kgf)^(−k)`.
/// Interlink's FSR integration guide shows conductance nearly proportional to force (`k ≈ 1`);
/// the defaults, `R₁` = 3 kΩ and `k` = 0.9, with the paper's rated range of the SF10-60 strip
/// (§2.2: 10 g – 5 kg), are the model the project's simulated hand uses.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields, default))]
pub struct FsrLaw {
    /// Resistance at 1 kgf, Ω.
    pub r_1kgf_ohm: f64,
    /// Power-law exponent `k` in `R ∝ F^(−k)`.
    pub exponent: f64,
    /// The divider's resistor to ground, Ω.
    pub divider_ohm: f64,
    /// The rated floor, N: less reads as 0 (no contact).
    pub min_force_n: f64,
    /// The rated ceiling, N: the reading saturates there.
    pub max_force_n: f64,
}

impl Default for FsrLaw {
    fn default() -> FsrLaw {
        FsrLaw {
            r_1kgf_ohm: 3_000.0,
            exponent: 0.9,
            divider_ohm: 10_000.0,
            min_force_n: 0.010 * KGF_N,
            max_force_n: 5.0 * KGF_N,
        }
    }
}

impl FsrLaw {
    /// The force a divider voltage `v` stands for with supply `vcc_v`: 0 below the rated
    /// floor, the ceiling at or above it; always finite, never negative.
    ///
    /// ```
    /// use underactuated_hand::calibration::FsrLaw;
    /// let fsr = FsrLaw::default();
    /// // 10 kΩ divider, 3 kΩ at 1 kgf: 5 V · 10 / 13 ≈ 3.846 V reads 1 kgf.
    /// assert!((fsr.force_n(5.0 * 10.0 / 13.0, 5.0) - 9.80665).abs() < 1e-9);
    /// assert_eq!(fsr.force_n(0.0, 5.0), 0.0);
    /// assert_eq!(fsr.force_n(5.0, 5.0), fsr.max_force_n);
    /// assert_eq!(fsr.force_n(f64::NAN, 5.0), 0.0);
    /// ```
    #[inline]
    pub fn force_n(&self, v: f64, vcc_v: f64) -> f64 {
        if v >= vcc_v {
            return self.max_force_n;
        }
        let r = self.divider_ohm * (vcc_v - v) / v;
        let f = KGF_N * (r / self.r_1kgf_ohm).powf(-1.0 / self.exponent);
        if f.is_nan() || f < self.min_force_n {
            0.0
        } else {
            f.min(self.max_force_n)
        }
    }

    /// What is wrong with the law, if anything (a non-positive resistance or exponent, a
    /// ceiling below the floor).
    pub fn check(&self) -> Result<(), &'static str> {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if !positive(self.r_1kgf_ohm) || !positive(self.exponent) || !positive(self.divider_ohm) {
            return Err("r_1kgf_ohm, exponent and divider_ohm must be finite and positive");
        }
        let floor_ok = self.min_force_n.is_finite() && self.min_force_n >= 0.0;
        let ceiling_ok = self.max_force_n.is_finite() && self.max_force_n > self.min_force_n;
        if !(floor_ok && ceiling_ok) {
            return Err("0 ≤ min_force_n < max_force_n, both finite");
        }
        Ok(())
    }
}

/// A linear rotary potentiometer (the paper's §2.3: 270° of electrical travel), its track
/// across the supply, mounted so that the open joint (0°) sits `zero_deg` along its travel.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields, default))]
pub struct PotMount {
    /// Electrical travel, degrees.
    pub travel_deg: f64,
    /// Where on its travel the open joint sits, degrees.
    pub zero_deg: f64,
}

impl Default for PotMount {
    /// 270° of travel, the open joint at 45° (the 90° joint range then stays inside the
    /// travel, as the paper notes).
    fn default() -> PotMount {
        PotMount {
            travel_deg: 270.0,
            zero_deg: 45.0,
        }
    }
}

impl PotMount {
    /// The joint angle a wiper voltage `v` stands for with supply `vcc_v`, degrees.
    ///
    /// ```
    /// use underactuated_hand::calibration::PotMount;
    /// let pot = PotMount::default();
    /// assert!((pot.angle_deg(2.5, 5.0) - 90.0).abs() < 1e-12); // mid-travel: 135° − 45°
    /// ```
    #[inline]
    pub fn angle_deg(&self, v: f64, vcc_v: f64) -> f64 {
        v / vcc_v * self.travel_deg - self.zero_deg
    }

    /// This mounting zeroed where it is: the open joint (0°) at the wiper voltage `v` read with
    /// the joint at its open stop, supply `vcc_v` — a potentiometer mounted a few degrees off
    /// reads the open joint as those degrees, and this takes them out.
    ///
    /// ```
    /// use underactuated_hand::calibration::PotMount;
    /// let pot = PotMount::default(); // the open joint expected at 45° of the travel
    /// let v = 50.0 / 270.0 * 5.0; // but read at 50°: mounted 5° off
    /// assert!((pot.angle_deg(v, 5.0) - 5.0).abs() < 1e-12);
    /// let zeroed = pot.zeroed_at(v, 5.0);
    /// assert!((zeroed.zero_deg - 50.0).abs() < 1e-12);
    /// assert!(zeroed.angle_deg(v, 5.0).abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn zeroed_at(&self, v: f64, vcc_v: f64) -> PotMount {
        PotMount {
            zero_deg: v / vcc_v * self.travel_deg,
            ..*self
        }
    }

    /// What is wrong with the mounting, if anything.
    pub fn check(&self) -> Result<(), &'static str> {
        if !(self.travel_deg.is_finite() && self.travel_deg > 0.0 && self.zero_deg.is_finite()) {
            return Err("travel_deg must be finite and positive, zero_deg finite");
        }
        Ok(())
    }
}

/// The calibration of the whole hand: the ADC's reference, one FSR law for the four strips,
/// and each finger's potentiometer mounting.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields, default))]
pub struct Calibration {
    /// The ADC's reference and the dividers' supply, V (an Uno's or Mega's 5 V).
    pub vref_v: f64,
    /// The FSR law, fingers 1–4.
    pub fsr: FsrLaw,
    /// Each finger's potentiometer, fingers 1–4.
    pub pot: [PotMount; 4],
}

impl Default for Calibration {
    fn default() -> Calibration {
        Calibration {
            vref_v: 5.0,
            fsr: FsrLaw::default(),
            pot: [PotMount::default(); 4],
        }
    }
}

impl Calibration {
    /// Finger `i`'s force, N, from its FSR channel's ADC code.
    #[inline]
    pub fn force_n(&self, code: u16) -> f64 {
        self.fsr.force_n(adc_volts(code, self.vref_v), self.vref_v)
    }

    /// Finger `finger`'s distal angle, degrees, from its potentiometer channel's ADC code.
    #[inline]
    pub fn angle_deg(&self, finger: usize, code: u16) -> f64 {
        self.pot[finger.min(3)].angle_deg(adc_volts(code, self.vref_v), self.vref_v)
    }

    /// One sample from the eight channels' codes (FSRs 1–4, then potentiometers 1–4): the four
    /// forces, N, then the four distal angles, degrees — the order of the softness classifier's
    /// inputs (the paper's §3.1).
    ///
    /// ```
    /// use underactuated_hand::calibration::Calibration;
    /// let s = Calibration::default().sample(&[0, 0, 0, 1023, 0, 256, 512, 1023]);
    /// assert_eq!(&s[..3], &[0.0, 0.0, 0.0]);
    /// assert!((s[7] - 224.87).abs() < 0.01);
    /// ```
    pub fn sample(&self, codes: &[u16; 8]) -> [f32; 8] {
        core::array::from_fn(|k| {
            if k < 4 {
                self.force_n(codes[k]) as f32
            } else {
                self.angle_deg(k - 4, codes[k]) as f32
            }
        })
    }

    /// What is wrong with the calibration, if anything.
    pub fn check(&self) -> Result<(), &'static str> {
        if !(self.vref_v.is_finite() && self.vref_v > 0.0) {
            return Err("vref_v must be finite and positive");
        }
        self.fsr.check()?;
        self.pot.iter().try_for_each(PotMount::check)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_decodes_to_a_finite_force_inside_the_rated_range() {
        let c = Calibration::default();
        let mut last = 0.0;
        for code in 0..=ADC_CODES + 5 {
            let f = c.force_n(code);
            assert!(
                f.is_finite() && f >= 0.0 && f <= c.fsr.max_force_n,
                "{code}: {f}"
            );
            assert!(f >= last, "monotonic in the code: {code}");
            last = f;
        }
    }

    #[test]
    fn a_bad_law_is_refused_in_words() {
        let mut c = Calibration::default();
        c.fsr.exponent = 0.0;
        assert!(c.check().unwrap_err().contains("exponent"));
        let mut c = Calibration::default();
        c.pot[2].travel_deg = -1.0;
        assert!(c.check().unwrap_err().contains("travel_deg"));
        assert!(Calibration::default().check().is_ok());
    }
}
