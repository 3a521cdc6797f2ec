//! Instructions per call of the fingertip's compute stages on a Cortex-M3 (soft-float) and a
//! Cortex-M4F, counted under QEMU: with `-icount shift=N` QEMU's virtual clock advances exactly
//! 2^N ns per executed instruction, and SysTick (on the core clock) is read against it. The
//! ticks-per-instruction ratio is calibrated in the program on a loop of known length, and each
//! stage runs 1 and 101 times so that start-up and the timer reads cancel: (ticks(101) −
//! ticks(1)) / 100 per call. The inputs are one fixed, realistic reading per stage; the contact
//! MLP's decode costs a little more or less on other inputs (its soft-float `exp` varies).
//!
//! Output, one line per stage: `stage NAME: X instructions per call` (parsed by `cargo xtask
//! firmware --write`). Instructions are not cycles: soft-float helpers, loads and flash wait
//! states add cycles, so these are lower bounds on cycles.

#![no_std]
#![no_main]

use core::hint::black_box;
use core::sync::atomic::{AtomicU32, Ordering};

use aot_locate::{AotLocator, AreaGrid, ArrivalEvent, Geometry};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::{SCB, SYST};
use cortex_m_rt::{entry, exception};
use cortex_m_semihosting::{debug, hprintln};
use hand_traits::{ContactLocator, GraspObservation, GraspPolicy};
use tactile_nets::contact_mlp::{TapReading, features};
use tactile_nets::pretrained::{
    CONTACT_MLP_OSR1024, FIXED_CONTACT_MLP_OSR1024, FIXED_FORCE_DNN_SIM, FORCE_DNN_SIM,
};

/// No heap, as the firmware (`firmware/fingertip/src/main.rs`): nothing measured allocates,
/// and `alloc`, which a linked crate brings in, needs an allocator to link.
struct NoHeap;

// `GlobalAlloc` is an unsafe trait; refusing (null) and freeing nothing meet its contract.
#[allow(unsafe_code)]
unsafe impl core::alloc::GlobalAlloc for NoHeap {
    unsafe fn alloc(&self, _: core::alloc::Layout) -> *mut u8 {
        core::ptr::null_mut()
    }
    unsafe fn dealloc(&self, _: *mut u8, _: core::alloc::Layout) {}
}

#[global_allocator]
static HEAP: NoHeap = NoHeap;

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

const RELOAD: u32 = 0x00FF_FFFF;
static WRAPS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    WRAPS.fetch_add(1, Ordering::Relaxed);
}

/// SysTick ticks since start, 64-bit: the wraps the exception counted, plus one whose
/// exception is still pending.
#[inline(never)]
fn now() -> u64 {
    cortex_m::interrupt::free(|_| {
        let mut wraps = WRAPS.load(Ordering::Relaxed);
        let mut current = SYST::get_current();
        if SCB::is_pendst_pending() {
            wraps += 1;
            current = SYST::get_current();
        }
        u64::from(wraps) * (u64::from(RELOAD) + 1) + u64::from(RELOAD - current)
    })
}

/// Exactly two instructions per iteration (`subs`, `bne`): the calibration's known length.
#[inline(never)]
fn spin(n: u32) {
    // The one `unsafe`: a loop whose instruction count the compiler cannot change.
    #[allow(unsafe_code)]
    unsafe {
        core::arch::asm!("1:", "subs {0}, #1", "bne 1b", inout(reg) n => _, options(nomem, nostack));
    }
}

fn ticks(f: impl FnOnce()) -> u64 {
    let t0 = now();
    f();
    now() - t0
}

/// Runs `work` `k` times, folding its results so that none is optimised away.
#[inline(never)]
fn repeat(k: u32, mut work: impl FnMut() -> u32) -> u32 {
    (0..k).fold(0, |acc, _| acc ^ black_box(work()))
}

const K1: u32 = 1;
const K2: u32 = 101;

#[entry]
fn main() -> ! {
    let Some(mut cp) = cortex_m::Peripherals::take() else {
        panic!("core peripherals taken twice");
    };
    cp.SYST.set_clock_source(SystClkSource::Core);
    cp.SYST.set_reload(RELOAD);
    cp.SYST.clear_current();
    cp.SYST.enable_interrupt();
    cp.SYST.enable_counter();
    // Let SysTick's first reload (and its exception) happen before anything is measured.
    spin(100_000);

    let (n1, n2) = (1_000u32, 1_001_000u32);
    let calibration_ticks = ticks(|| spin(black_box(n2))) - ticks(|| spin(black_box(n1)));
    let calibration_insns = 2 * u64::from(n2 - n1);
    let per_call = |a: u64, b: u64| {
        (b - a) as f64 * calibration_insns as f64 / calibration_ticks as f64 / f64::from(K2 - K1)
    };
    let measure = |name: &str, work: &mut dyn FnMut() -> u32| {
        let a = ticks(|| {
            black_box(repeat(K1, &mut *work));
        });
        let b = ticks(|| {
            black_box(repeat(K2, &mut *work));
        });
        hprintln!(
            "stage {}: {:.0} instructions per call",
            name,
            per_call(a, b)
        );
    };

    // A tap near sensor 3, as the host harness's presses read at OSR 1024.
    let reading = TapReading {
        baseline_pa: [101_000.0, 101_020.0, 100_990.0],
        held_pa: [102_500.0, 101_820.0, 103_490.0],
        arrival_ms: [Some(0.0), Some(2.5), Some(1.2)],
    };
    let rise_hpa = [15.0f32, 8.0, 25.0];
    let observation = GraspObservation {
        pressure_error_pa: 200.0,
        pressure_rate_pa_per_s: 1_500.0,
    };
    let event = ArrivalEvent {
        pressure_pa: [1_500.0, 800.0, 2_500.0],
        arrival_us: [Some(0), Some(2_500), Some(1_200)],
    };
    let t0 = now();
    let mut grasp = fuzzy_mamdani::grasp_controller();
    let construction = now() - t0;
    // The fingertip firmware's pad (`fingertip::PAD`, `fingertip::SENSORS_MM`: 18 × 12 mm, an
    // inverted triangle of sensors): eq. 3's work per call does not depend on where the
    // sensors sit, but these are the numbers the firmware computes with.
    let pad = AreaGrid {
        width_mm: 18.0,
        height_mm: 12.0,
    };
    let Ok(geometry) = Geometry::new([[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]], pad) else {
        panic!("a sensor on an area centre");
    };
    let mut aot = AotLocator::new(geometry);

    // The check: a loop of 1000 instructions (plus the call) measured like a stage.
    measure("check-spin-1000", &mut || {
        spin(black_box(500));
        0
    });
    measure("contact-mlp", &mut || {
        let p = CONTACT_MLP_OSR1024.predict(&features(black_box(&reading)));
        p.map_or(u32::MAX, |p| u32::from(p.region) ^ p.contact)
    });
    measure("force-dnn", &mut || {
        let g = FORCE_DNN_SIM.estimate_gf(black_box(&rise_hpa[..]));
        g.map_or(u32::MAX, f32::to_bits)
    });
    measure("fixed-contact-mlp", &mut || {
        let p = FIXED_CONTACT_MLP_OSR1024.predict(&features(black_box(&reading)));
        p.map_or(u32::MAX, |p| u32::from(p.region) ^ p.contact)
    });
    measure("fixed-force-dnn", &mut || {
        let g = FIXED_FORCE_DNN_SIM.estimate_gf(black_box(&rise_hpa[..]));
        g.map_or(u32::MAX, f32::to_bits)
    });
    measure("fuzzy-grasp", &mut || {
        let e = grasp.effort(black_box(&observation));
        e.map_or(u32::MAX, |e| u32::from(e.to_torque_limit_raw()))
    });
    measure("aot", &mut || {
        let c = aot.locate(black_box(&event));
        c.map_or(u32::MAX, |c| u32::from(c.region))
    });
    hprintln!(
        "stage fuzzy-construction: {:.0} instructions per call",
        construction as f64 * calibration_insns as f64 / calibration_ticks as f64
    );
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}
