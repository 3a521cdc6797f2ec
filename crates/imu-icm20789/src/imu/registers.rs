//! IMU register map (DS-000169 §12–13, register map; the MPU-6500 family layout).

/// Sample-rate divider: ODR = 1 kHz / (1 + SMPLRT_DIV) while the DLPF is on.
pub const SMPLRT_DIV: u8 = 0x19;
/// FIFO mode (bit 6) and gyro DLPF_CFG (bits 2:0).
pub const CONFIG: u8 = 0x1A;
/// Gyro FS_SEL (bits 4:3) and FCHOICE_B (bits 1:0).
pub const GYRO_CONFIG: u8 = 0x1B;
/// Accel FS_SEL (bits 4:3).
pub const ACCEL_CONFIG: u8 = 0x1C;
/// Accel FCHOICE_B (bit 3) and A_DLPF_CFG (bits 2:0).
pub const ACCEL_CONFIG2: u8 = 0x1D;
/// Which sensors feed the FIFO: TEMP (bit 7), XG/YG/ZG (bits 6:4), ACCEL (bit 3).
pub const FIFO_EN: u8 = 0x23;
/// Interrupt pin / bypass configuration; BYPASS_EN is bit 1.
pub const INT_PIN_CFG: u8 = 0x37;
/// First of the 14 data registers: ACCEL_X/Y/Z, TEMP, GYRO_X/Y/Z, big-endian.
pub const ACCEL_XOUT_H: u8 = 0x3B;
/// User control: FIFO_EN (bit 6), I2C_IF_DIS (bit 4), FIFO_RST (bit 2).
pub const USER_CTRL: u8 = 0x6A;
/// Power management 1: DEVICE_RESET (bit 7), SLEEP (bit 6), CLKSEL (bits 2:0).
pub const PWR_MGMT_1: u8 = 0x6B;
/// Power management 2: per-axis standby bits (0 = all on).
pub const PWR_MGMT_2: u8 = 0x6C;
/// FIFO byte count, high byte (low byte follows at 0x73).
pub const FIFO_COUNTH: u8 = 0x72;
/// FIFO read port: every read pops the next byte.
pub const FIFO_R_W: u8 = 0x74;
/// Device ID.
pub const WHO_AM_I: u8 = 0x75;

/// INT_PIN_CFG: route the auxiliary I2C pins to the main bus (reaches the barometer).
pub const BYPASS_EN: u8 = 1 << 1;
/// PWR_MGMT_1: reset all registers.
pub const DEVICE_RESET: u8 = 1 << 7;
/// PWR_MGMT_1: sleep; set after reset (reset value 0x41).
pub const SLEEP: u8 = 1 << 6;
/// PWR_MGMT_1: CLKSEL = 1, best available clock (gyro PLL when ready).
pub const CLKSEL_AUTO: u8 = 0x01;
/// USER_CTRL: enable the FIFO.
pub const USER_FIFO_EN: u8 = 1 << 6;
/// USER_CTRL: reset (empty) the FIFO; self-clearing.
pub const FIFO_RST: u8 = 1 << 2;
/// FIFO_EN: gyro X, Y, Z and accel into the FIFO (12 bytes per sample).
pub const FIFO_ACCEL_GYRO: u8 = 0b0111_1000;

/// WHO_AM_I value of the ICM-20789.
pub const WHO_AM_I_ICM20789: u8 = 0x03;
/// WHO_AM_I value of the ICM-20789's first silicon revision (R1).
pub const WHO_AM_I_ICM20789_R1: u8 = 0x02;
/// Reset value of PWR_MGMT_1 (asleep, CLKSEL = 1).
pub const PWR_MGMT_1_RESET: u8 = 0x41;
/// Wait after DEVICE_RESET before the next access, µs (100 ms as in the reference drivers).
pub const RESET_TIME_US: u32 = 100_000;
/// Bytes in one FIFO record with accel + gyro enabled.
pub const FIFO_RECORD_LEN: usize = 12;
/// FIFO capacity, bytes (DS-000169 §1: "4 kB FIFO").
pub const FIFO_CAPACITY: usize = 4096;
