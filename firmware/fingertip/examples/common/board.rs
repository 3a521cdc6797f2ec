//! The board's bus on the host: three MS5611 chip models behind a TCA9548A model (sensor `k`
//! on channel `k`, CSB low), each reading its pressure from hand-sim's fingertip physics.

use std::cell::RefCell;
use std::rc::Rc;

use baro_drivers::sim::{BusTiming, Conditions, I2cTarget, Ms5611Sim, SimClock, Tca9548aSim};
use hand_sim::fingertip::FingertipPhysics;

/// The pad's temperature under the silicone, °C.
const PAD_CELSIUS: f64 = 24.0;

/// The switch with its three sensors, on `clock`; chip `k`'s noise seeded `seed + k`.
pub fn mux(
    physics: &Rc<RefCell<FingertipPhysics>>,
    clock: &SimClock,
    seed: u64,
) -> Tca9548aSim<impl I2cTarget> {
    let mut mux = Tca9548aSim::new(0x70, clock.clone(), BusTiming::default());
    for k in 0..3u8 {
        let physics = Rc::clone(physics);
        let env = move |now_ns: u64| Conditions {
            pressure_mbar: physics.borrow_mut().pressure_hpa(usize::from(k), now_ns),
            temperature_celsius: PAD_CELSIUS,
        };
        let chip = Ms5611Sim::new(env, clock.clone())
            .with_seed(seed + u64::from(k))
            .with_command_log(false);
        mux = mux.attach(k, chip);
    }
    mux
}
