//! A tactile device as a node, laid out after TakkTile's ROS driver: under the device's
//! namespace, `tactile/raw` (each frame as read), `tactile/touch` (tared: the zero of each
//! sensor subtracted), `tactile/sensor_info` (about once a second) and the service
//! `tactile/tare` (`std_srvs/Trigger`: the latest raw frame becomes the zero).
//!
//! ```no_run
//! use hand_traits::{PressureFrame, TactileSource};
//! use hand_zenoh::node::{Node, NodeOptions};
//! use hand_zenoh::tactile::{TactileNode, TactileInfo};
//!
//! # struct Fingertip;
//! # impl TactileSource for Fingertip {
//! #     type Frame = PressureFrame<3>;
//! #     type Error = ();
//! #     fn read_frame(&mut self) -> Result<PressureFrame<3>, ()> { Ok(PressureFrame { t_us: 0, pressure_pa: [101_325.0; 3] }) }
//! # }
//! let node = Node::open(NodeOptions::new("/hand0", "tactile"))?;
//! let info = TactileInfo { chip: "MS5611".into(), rate_hz: 100.0, frame_id: "hand0/fingertip0".into() };
//! let mut tactile = TactileNode::new(&node, Fingertip, info)?;
//! tactile.step()?; // read one frame, publish raw and touch (and sensor_info when due)
//! # Ok::<(), hand_zenoh::tactile::TactileError<()>>(())
//! ```

use crate::NodeError;
use crate::msg::handstack_msgs::{PressureFrame, SensorInfo};
use crate::msg::std_srvs::{Trigger, TriggerResponse};
use crate::node::{Node, Publisher, ServiceServer, now_ns};
use hand_traits::TactileSource;
use std::sync::{Arc, Mutex, PoisonError};

/// What the node says about its device.
#[derive(Debug, Clone, PartialEq)]
pub struct TactileInfo {
    /// The chip (`MS5611`).
    pub chip: String,
    /// Frames per second the device is read at.
    pub rate_hz: f32,
    /// The frame id every message carries (`hand0/fingertip0`).
    pub frame_id: String,
}

/// Why a step failed.
#[derive(Debug, thiserror::Error)]
pub enum TactileError<E: core::fmt::Debug> {
    /// The device did not give a frame (the node publishes nothing for it).
    #[error("tactile device: {0:?}")]
    Device(E),
    /// A frame with a value that is not finite: dropped, not published.
    #[error("sensor {sensor} read {value} Pa")]
    NotFinite {
        /// Which sensor.
        sensor: usize,
        /// What it read.
        value: f32,
    },
    /// Publishing failed.
    #[error(transparent)]
    Node(#[from] NodeError),
}

#[derive(Debug, Default)]
struct Zero {
    latest: Option<Vec<f32>>,
    tare: Vec<f32>,
}

/// A tactile source published as a node.
pub struct TactileNode<S> {
    source: S,
    info: TactileInfo,
    raw: Publisher<PressureFrame>,
    touch: Publisher<PressureFrame>,
    sensor_info: Publisher<SensorInfo>,
    zero: Arc<Mutex<Zero>>,
    tare: ServiceServer,
    frames: u64,
}

impl<S, const N: usize> TactileNode<S>
where
    S: TactileSource<Frame = hand_traits::PressureFrame<N>>,
{
    /// Declares the device's topics and tare service on `node`.
    pub fn new(node: &Node, source: S, info: TactileInfo) -> Result<Self, NodeError> {
        let zero = Arc::new(Mutex::new(Zero {
            latest: None,
            tare: vec![0.0; N],
        }));
        let shared = Arc::clone(&zero);
        let tare = node.service::<Trigger, _>("tactile/tare", move |_| {
            let mut z = shared.lock().unwrap_or_else(PoisonError::into_inner);
            match z.latest.clone() {
                Some(latest) => {
                    let text = format!("tared at {latest:?} Pa");
                    z.tare = latest;
                    TriggerResponse {
                        success: true,
                        message: text,
                    }
                }
                None => TriggerResponse {
                    success: false,
                    message: "no frame read yet: nothing to tare at".to_owned(),
                },
            }
        })?;
        Ok(TactileNode {
            raw: node.publisher("tactile/raw")?,
            touch: node.publisher("tactile/touch")?,
            sensor_info: node.publisher("tactile/sensor_info")?,
            source,
            info,
            zero,
            tare,
            frames: 0,
        })
    }

    /// Reads one frame and publishes it raw and tared; every `rate_hz` frames (and on the
    /// first) also the sensor info. Returns the raw frame.
    pub fn step(&mut self) -> Result<hand_traits::PressureFrame<N>, TactileError<S::Error>> {
        let frame = self.source.read_frame().map_err(TactileError::Device)?;
        if let Some((sensor, &value)) = frame
            .pressure_pa
            .iter()
            .enumerate()
            .find(|(_, v)| !v.is_finite())
        {
            return Err(TactileError::NotFinite { sensor, value });
        }
        let header = crate::convert::header(now_ns(), &self.info.frame_id);
        let tare = {
            let mut z = self.zero.lock().unwrap_or_else(PoisonError::into_inner);
            z.latest = Some(frame.pressure_pa.to_vec());
            z.tare.clone()
        };
        let mut msg = PressureFrame {
            header: header.clone(),
            pressure_pa: frame.pressure_pa.to_vec(),
        };
        self.raw.publish(&msg)?;
        for (p, t) in msg.pressure_pa.iter_mut().zip(&tare) {
            *p -= t;
        }
        self.touch.publish(&msg)?;
        let every = self.info.rate_hz.max(1.0) as u64;
        if self.frames % every == 0 {
            self.sensor_info.publish(&SensorInfo {
                header,
                chip: self.info.chip.clone(),
                sensor_count: N as u8,
                rate_hz: self.info.rate_hz,
                tare_pa: tare,
            })?;
        }
        self.frames += 1;
        Ok(frame)
    }

    /// The `tactile/raw` publisher (its key and GID).
    pub fn raw(&self) -> &Publisher<PressureFrame> {
        &self.raw
    }

    /// Tare requests answered so far.
    pub fn tares(&self) -> u64 {
        self.tare.handled()
    }
}
