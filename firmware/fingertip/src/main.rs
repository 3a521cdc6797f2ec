//! The fingertip firmware: start-up, then one [`fingertip::Fingertip::cycle`] and one UART frame
//! per cycle, for ever. A failed cycle sends a fault frame (torque 0, the safe state) and the
//! next cycle tries again; a sensor that fails at start-up halts with nothing sent.
//!
//! Boards (pins as on their common breakout boards):
//!
//! | target | MCU | I2C1 (to the TCA9548A at 0x70) | USART1 TX, 460 800 Bd |
//! |---|---|---|---|
//! | `thumbv7m-none-eabi` (Cortex-M3) | STM32F103RE, 72 MHz, 512 KiB flash, 64 KiB RAM | PB6 SCL, PB7 SDA, 400 kHz | PA9 |
//! | the same, `--no-default-features --features stm32f103c8` | STM32F103C8 ("Blue Pill"), 72 MHz, 64 KiB flash, 20 KiB RAM | PB6 SCL, PB7 SDA, 400 kHz | PA9 |
//! | `thumbv7em-none-eabihf` (Cortex-M4F) | STM32F411CE, 96 MHz, 512 KiB flash, 128 KiB RAM | PB6 SCL, PB7 SDA, 400 kHz | PA9 |
//!
//! Built on the host it is a stub that says so: the pipeline runs on the host through
//! `examples/host_cycles.rs`.

#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "the fingertip firmware runs on a Cortex-M: build it with \
         --target thumbv7m-none-eabi or thumbv7em-none-eabihf (docs/embedded.md); \
         on the host, run `cargo run --release --example host_cycles`"
    );
}

#[cfg(target_os = "none")]
mod board {
    use aot_locate::Geometry;
    use core::alloc::{GlobalAlloc, Layout};
    use cortex_m::peripheral::{DCB, DWT};
    use embedded_io::Write;
    use fingertip::{Config, Fingertip, PAD, SENSORS_MM, frame};
    use panic_halt as _;

    /// No heap: the firmware allocates nothing, at start-up or after (the weights are
    /// `'static`, the fuzzy preset's tables fixed-size, every buffer the pipeline's own). A
    /// linked crate (fuzzy-mamdani's general engine, unused here) brings in `alloc`, which
    /// needs an allocator to link; this one refuses every request, so an allocation would end
    /// in the panic handler instead of taking RAM.
    struct NoHeap;

    // The one `unsafe` of the firmware: `GlobalAlloc` is an unsafe trait. Refusing (null) and
    // freeing nothing meet its contract.
    #[allow(unsafe_code)]
    unsafe impl GlobalAlloc for NoHeap {
        unsafe fn alloc(&self, _: Layout) -> *mut u8 {
            core::ptr::null_mut()
        }
        unsafe fn dealloc(&self, _: *mut u8, _: Layout) {}
    }

    #[global_allocator]
    static HEAP: NoHeap = NoHeap;

    /// I2C clock to the TCA9548A and the MS5611s (both allow 400 kHz), kHz.
    const I2C_KHZ: u32 = 400;
    /// UART to the host: a 28-byte frame takes 0.6 ms, inside the 6 ms cycle.
    const BAUD: u32 = fingertip_link::BAUD;

    /// A monotonic µs clock from the DWT cycle counter (wraps every ~60 s at 72 MHz; the sum
    /// of wrapping differences does not, if it is read at least that often — every cycle).
    struct Micros {
        last: u32,
        cycles: u64,
        per_us: u64,
    }

    impl Micros {
        /// Starts the cycle counter of a core clocked at `sysclk_hz`.
        fn start(dcb: &mut DCB, dwt: &mut DWT, sysclk_hz: u32) -> Micros {
            dcb.enable_trace();
            dwt.enable_cycle_counter();
            Micros {
                last: DWT::cycle_count(),
                cycles: 0,
                per_us: u64::from(sysclk_hz / 1_000_000).max(1),
            }
        }

        fn now_us(&mut self) -> u64 {
            let now = DWT::cycle_count();
            self.cycles += u64::from(now.wrapping_sub(self.last));
            self.last = now;
            self.cycles / self.per_us
        }
    }

    /// Stops for good, sleeping (a board without its peripherals or sensors has nothing to do).
    fn halt() -> ! {
        loop {
            cortex_m::asm::wfi();
        }
    }

    /// The loop over a started board: `i2c` reaches the TCA9548A, `tx` the host.
    fn run<I2C, D, W>(i2c: I2C, delay: &mut D, tx: &mut W, clock: &mut Micros) -> !
    where
        I2C: embedded_hal::i2c::I2c,
        D: embedded_hal::delay::DelayNs,
        W: Write,
    {
        let switch = xca9548a::Xca9548a::new(i2c, xca9548a::SlaveAddr::default());
        let parts = switch.split();
        let sensors = [parts.i2c0, parts.i2c1, parts.i2c2]
            .map(|port| baro_drivers::Ms5611::new_with_i2c(port, baro_drivers::Address::CsbLow));
        let Ok(pad) = Geometry::new(SENSORS_MM, PAD) else {
            // A sensor on an area centre: not the board's pad (a constant; never here).
            halt();
        };
        let Ok(mut tip) = Fingertip::new(sensors, delay, Config::DEFAULT, pad) else {
            // A sensor missing or a PROM failing its CRC: nothing to measure with.
            halt();
        };
        let mut seq = 0u8;
        loop {
            let t_us = clock.now_us();
            let bytes = match tip.cycle(delay, t_us) {
                Ok(estimate) => frame::encode(&estimate, seq),
                Err(_) => frame::fault(t_us, seq),
            };
            // A UART that fails to take a frame loses that frame only.
            let _ = tx.write_all(&bytes);
            seq = seq.wrapping_add(1);
        }
    }

    #[cfg(target_abi = "eabi")]
    #[cortex_m_rt::entry]
    fn main() -> ! {
        use stm32f1xx_hal::i2c::{DutyCycle, I2c, Mode};
        use stm32f1xx_hal::{pac, prelude::*, rcc, serial};

        let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), pac::CorePeripherals::take())
        else {
            halt();
        };
        let mut flash = dp.FLASH.constrain();
        let mut rcc = dp
            .RCC
            .freeze(rcc::Config::hse(8.MHz()).sysclk(72.MHz()), &mut flash.acr);
        let mut clock = Micros::start(&mut cp.DCB, &mut cp.DWT, rcc.clocks.sysclk().raw());
        let mut gpioa = dp.GPIOA.split(&mut rcc);
        let gpiob = dp.GPIOB.split(&mut rcc);
        let i2c = I2c::new(
            dp.I2C1,
            (gpiob.pb6, gpiob.pb7),
            Mode::fast(I2C_KHZ.kHz(), DutyCycle::Ratio2to1),
            &mut rcc,
        );
        let tx_pin = gpioa.pa9.into_alternate_push_pull(&mut gpioa.crh);
        let mut tx = dp.USART1.tx(
            tx_pin,
            serial::Config::default().baudrate(BAUD.bps()),
            &mut rcc,
        );
        let mut delay = dp.TIM2.delay_us(&mut rcc);
        run(i2c, &mut delay, &mut tx, &mut clock)
    }

    #[cfg(target_abi = "eabihf")]
    #[cortex_m_rt::entry]
    fn main() -> ! {
        use stm32f4xx_hal::i2c::{I2c, Mode};
        use stm32f4xx_hal::{pac, prelude::*, rcc};

        let (Some(dp), Some(mut cp)) = (pac::Peripherals::take(), pac::CorePeripherals::take())
        else {
            halt();
        };
        let mut rcc = dp.RCC.freeze(rcc::Config::hse(25.MHz()).sysclk(96.MHz()));
        let mut clock = Micros::start(&mut cp.DCB, &mut cp.DWT, rcc.clocks.sysclk().raw());
        let gpioa = dp.GPIOA.split(&mut rcc);
        let gpiob = dp.GPIOB.split(&mut rcc);
        let i2c = I2c::new(
            dp.I2C1,
            (gpiob.pb6, gpiob.pb7),
            Mode::fast(I2C_KHZ.kHz(), stm32f4xx_hal::i2c::DutyCycle::Ratio2to1),
            &mut rcc,
        );
        let Ok(mut tx) = dp.USART1.tx(gpioa.pa9, BAUD.bps(), &mut rcc) else {
            halt();
        };
        let mut delay = dp.TIM2.delay_us(&mut rcc);
        run(i2c, &mut delay, &mut tx, &mut clock)
    }
}
