//! A tactile device as a node, laid out after TakkTile's ROS driver: under the device's
//! namespace, `tactile/raw` (each frame as read), `tactile/touch` (tared: the zero of each
//! sensor subtracted), `tactile/sensor_info` (about once a second) and the service
//! `tactile/tare` (`std_srvs/Trigger`: the latest raw frame becomes the zero). With a force
//! estimator ([`TactileNode::with_force`]) also `force` (`geometry_msgs/WrenchStamped`, see
//! [`crate::force`]) from each tared frame.
//!
//! ```no_run
//! use hand_traits::{PressureFrame, TactileSource};
//! use hand_zenoh::node::{Node, NodeOptions};
//! use hand_zenoh::tactile::{TactileNode, TactileInfo};
//!
//! # struct Fingertip;
//! # impl TactileSource for Fingertip {
//! #     type Frame = PressureFrame<3>;
//! #     type Error = core::convert::Infallible;
//! #     fn read_frame(&mut self) -> Result<PressureFrame<3>, Self::Error> { Ok(PressureFrame { t_us: 0, pressure_pa: [101_325.0; 3] }) }
//! # }
//! let node = Node::open(NodeOptions::new("/hand0", "tactile"))?;
//! let info = TactileInfo { chip: "MS5611".into(), rate_hz: 100.0, frame_id: "hand0/fingertip0".into() };
//! let mut tactile = TactileNode::new(&node, Fingertip, info)?;
//! tactile.step()?; // read one frame, publish raw and touch (and sensor_info when due)
//! # Ok::<(), hand_zenoh::tactile::TactileError<core::convert::Infallible>>(())
//! ```

use crate::NodeError;
use crate::force::{ForceTopic, rise_hpa};
use crate::msg::handstack_msgs::{PressureFrame, SensorInfo};
use crate::msg::std_srvs::{Trigger, TriggerResponse};
use crate::node::{Node, Publisher, ServiceServer, now_ns};
use hand_traits::{ForceEstimator, TactileSource};
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
pub enum TactileError<E: core::fmt::Debug + core::fmt::Display> {
    /// The device did not give a frame (the node publishes nothing for it).
    #[error("tactile device: {0}")]
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
    /// The zero was taken (by the service or the start-up tare), so `touch` is tared.
    set: bool,
}

/// The start-up tare of a node with a force estimator: the mean of its first frames.
#[derive(Debug)]
struct StartupTare {
    frames: u32,
    sum: Vec<f64>,
    seen: u32,
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
    force: Option<ForceTopic>,
    startup: Option<StartupTare>,
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
            set: false,
        }));
        let shared = Arc::clone(&zero);
        let tare = node.service::<Trigger, _>("tactile/tare", move |_| {
            let mut z = shared.lock().unwrap_or_else(PoisonError::into_inner);
            match z.latest.clone() {
                Some(latest) => {
                    let text = format!("tared at {latest:?} Pa");
                    z.tare = latest;
                    z.set = true;
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
            force: None,
            startup: None,
        })
    }

    /// Also publishes `force` from `estimator` on each frame once the node has a zero: the
    /// tare service's, or before anyone calls it, the mean of the first `tare_frames` frames
    /// (0: only the service's), which then tares `touch` too. No force is published before a
    /// zero: the estimator reads rises over the unloaded pad, not absolute pressures.
    pub fn with_force<F>(
        mut self,
        node: &Node,
        estimator: F,
        tare_frames: u32,
    ) -> Result<Self, NodeError>
    where
        F: ForceEstimator<Input = [f32]> + Send + 'static,
        F::Error: core::fmt::Debug + core::fmt::Display,
    {
        self.force = Some(ForceTopic::new(node, estimator)?);
        self.startup = (tare_frames > 0).then(|| StartupTare {
            frames: tare_frames,
            sum: vec![0.0; N],
            seen: 0,
        });
        Ok(self)
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
        let (tare, tared) = {
            let mut z = self.zero.lock().unwrap_or_else(PoisonError::into_inner);
            z.latest = Some(frame.pressure_pa.to_vec());
            if z.set {
                self.startup = None;
            } else if let Some(s) = &mut self.startup {
                for (sum, &p) in s.sum.iter_mut().zip(&frame.pressure_pa) {
                    *sum += f64::from(p);
                }
                s.seen += 1;
                if s.seen == s.frames {
                    z.tare = s
                        .sum
                        .iter()
                        .map(|v| (v / f64::from(s.frames)) as f32)
                        .collect();
                    z.set = true;
                    self.startup = None;
                }
            }
            (z.tare.clone(), z.set)
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
        if let (Some(force), true) = (&mut self.force, tared) {
            force.publish(header.clone(), &rise_hpa(&frame.pressure_pa, &tare))?;
        }
        let every = self.info.rate_hz.max(1.0) as u64;
        if self.frames.is_multiple_of(every) {
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

    /// The `force` topic, when the node has a force estimator.
    pub fn force(&self) -> Option<&ForceTopic> {
        self.force.as_ref()
    }

    /// Tare requests answered so far.
    pub fn tares(&self) -> u64 {
        self.tare.handled()
    }
}
