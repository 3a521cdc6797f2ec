//! The IMU half of the chip model: register file, sampled data registers, FIFO.

use std::collections::VecDeque;

use crate::imu::config::{AccelScale, GyroDlpf, GyroScale, imu_temperature_raw, output_rate_hz};
use crate::imu::registers as reg;
use crate::imu::{BURST_LEN, RawImu};
use crate::sim::environment::Environment;
use crate::sim::noise::{NoiseSource, SimNoise};

const DLPF_BY_BITS: [GyroDlpf; 8] = [
    GyroDlpf::Hz250,
    GyroDlpf::Hz176,
    GyroDlpf::Hz92,
    GyroDlpf::Hz41,
    GyroDlpf::Hz20,
    GyroDlpf::Hz10,
    GyroDlpf::Hz5,
    GyroDlpf::Hz3281,
];

#[derive(Debug)]
pub(crate) struct ImuModel {
    regs: [u8; 128],
    who_am_i: u8,
    /// Index of the sample held in the data registers, and its counts.
    held: Option<(u64, RawImu)>,
    fifo: VecDeque<u8>,
    /// Last sample index pushed to the FIFO.
    fifo_index: u64,
}

impl ImuModel {
    pub(crate) fn new(who_am_i: u8) -> Self {
        let mut model = ImuModel {
            regs: [0; 128],
            who_am_i,
            held: None,
            fifo: VecDeque::new(),
            fifo_index: 0,
        };
        model.reset();
        model
    }

    fn reset(&mut self) {
        self.regs = [0; 128];
        self.regs[usize::from(reg::PWR_MGMT_1)] = reg::PWR_MGMT_1_RESET;
        self.regs[usize::from(reg::WHO_AM_I)] = self.who_am_i;
        self.held = None;
        self.fifo.clear();
    }

    pub(crate) fn bypass_enabled(&self) -> bool {
        self.regs[usize::from(reg::INT_PIN_CFG)] & reg::BYPASS_EN != 0
    }

    fn asleep(&self) -> bool {
        self.regs[usize::from(reg::PWR_MGMT_1)] & reg::SLEEP != 0
    }

    fn sample_period_ns(&self) -> u64 {
        let dlpf = DLPF_BY_BITS[usize::from(self.regs[usize::from(reg::CONFIG)] & 0b111)];
        let rate = output_rate_hz(dlpf, self.regs[usize::from(reg::SMPLRT_DIV)]);
        (1e9 / f64::from(rate)) as u64
    }

    /// Counts of sample `index` (taken at `index · period`), with noise.
    fn measure(
        &self,
        index: u64,
        period_ns: u64,
        env: &mut dyn Environment,
        noise: &mut NoiseSource,
        sim: &SimNoise,
    ) -> RawImu {
        let truth = env.state(index * period_ns / 1_000);
        let accel = AccelScale::from_register(self.regs[usize::from(reg::ACCEL_CONFIG)]);
        let gyro = GyroScale::from_register(self.regs[usize::from(reg::GYRO_CONFIG)]);
        let mut noisy = |v: f32, sigma: f32| v + noise.gaussian(f64::from(sigma)) as f32;
        RawImu {
            accel: truth
                .accel_mps2
                .map(|a| accel.to_raw(noisy(a, sim.accel_mps2_rms))),
            temp: imu_temperature_raw(truth.temperature_c),
            gyro: truth
                .gyro_rps
                .map(|g| gyro.to_raw(noisy(g, sim.gyro_rps_rms))),
        }
    }

    /// Brings data registers and FIFO up to simulated time `now_ns`.
    pub(crate) fn update(
        &mut self,
        now_ns: u64,
        env: &mut dyn Environment,
        noise: &mut NoiseSource,
        sim: &SimNoise,
    ) {
        if self.asleep() {
            return;
        }
        let period = self.sample_period_ns();
        let index = now_ns / period;
        let fifo_on = self.regs[usize::from(reg::USER_CTRL)] & reg::USER_FIFO_EN != 0
            && self.regs[usize::from(reg::FIFO_EN)] & reg::FIFO_ACCEL_GYRO == reg::FIFO_ACCEL_GYRO;
        if fifo_on {
            // Every sample since the last update enters the FIFO; the oldest fall out when full.
            let first = self.fifo_index + 1;
            let skip = (index + 1)
                .saturating_sub(first)
                .saturating_sub((reg::FIFO_CAPACITY / reg::FIFO_RECORD_LEN) as u64);
            for k in first + skip..=index {
                let raw = self.measure(k, period, env, noise, sim);
                let bytes = raw.to_bytes();
                self.fifo.extend(bytes[..6].iter().chain(&bytes[8..]));
                while self.fifo.len() > reg::FIFO_CAPACITY {
                    self.fifo.drain(..reg::FIFO_RECORD_LEN);
                }
                if k == index {
                    self.held = Some((k, raw));
                }
            }
            self.fifo_index = self.fifo_index.max(index);
        }
        if self.held.map(|(k, _)| k) != Some(index) {
            self.held = Some((index, self.measure(index, period, env, noise, sim)));
        }
    }

    pub(crate) fn write(&mut self, register: u8, value: u8, now_ns: u64) {
        let r = usize::from(register & 0x7F);
        match register {
            reg::WHO_AM_I => {}
            reg::PWR_MGMT_1 if value & reg::DEVICE_RESET != 0 => self.reset(),
            reg::USER_CTRL => {
                if value & reg::FIFO_RST != 0 {
                    self.fifo.clear();
                    self.fifo_index = now_ns / self.sample_period_ns();
                }
                self.regs[r] = value & !reg::FIFO_RST;
            }
            _ => self.regs[r] = value,
        }
    }

    pub(crate) fn read(&mut self, register: u8) -> u8 {
        let data = usize::from(reg::ACCEL_XOUT_H)..usize::from(reg::ACCEL_XOUT_H) + BURST_LEN;
        let r = usize::from(register & 0x7F);
        let count = self.fifo.len() as u16;
        match register {
            _ if data.contains(&r) => {
                let bytes = self
                    .held
                    .map(|(_, raw)| raw.to_bytes())
                    .unwrap_or([0; BURST_LEN]);
                bytes[r - data.start]
            }
            reg::FIFO_COUNTH => (count >> 8) as u8,
            0x73 => count as u8,
            reg::FIFO_R_W => self.fifo.pop_front().unwrap_or(0xFF),
            _ => self.regs[r],
        }
    }
}
