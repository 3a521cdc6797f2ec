//! A rosbag2 bag with MCAP storage, written as ROS 2 Jazzy's rosbag2 writes one, and kept
//! readable while it is written.
//!
//! The layout follows rosbag2 0.26.5 (ROS 2 Jazzy; the format Kilted reads too):
//! - `metadata.yaml` (version 9) is `rosbag2_storage/include/rosbag2_storage/yaml.hpp`'s
//!   `convert<BagMetadata>::encode` under the key `rosbag2_bagfile_information`
//!   (`rosbag2_storage/src/rosbag2_storage/metadata_io.cpp`), each topic's
//!   `offered_qos_profiles` a list of `convert<rclcpp::QoS>::encode` maps with version 9's
//!   policy names (`rosbag2_storage/src/rosbag2_storage/qos.cpp`);
//! - the `.mcap` is `rosbag2_storage_mcap/src/mcap_storage.cpp`'s: profile `ros2`, no chunk
//!   compression (its default), one schema per type (encoding `ros2msg`, the full definition
//!   text), one channel per topic (message encoding `cdr`, metadata `offered_qos_profiles` as
//!   a YAML string and `topic_type_hash`), log and publish time the receive time (ns since the
//!   Unix epoch), and at the end a `rosbag2` metadata record holding the bag's metadata.
//!
//! **A killed recorder leaves a readable bag.** Chunks are built in memory and reach the file
//! whole, at most a second apart, each followed by an MCAP footer whose summary offset is 0
//! ("no summary: scan the data"), which the next chunk overwrites; `metadata.yaml` is
//! rewritten (write, then rename) at the same moments. Whatever kills the process, the file
//! ends in a footer and holds every message up to its last flush, and `metadata.yaml` counts
//! them. A clean end writes the real summary and footer.

use super::RecordError;
use hand_zenoh::cdr::CdrWriter;
use hand_zenoh::msg::Message;
use hand_zenoh::types::type_hash;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How often the chunk in memory reaches the file (and `metadata.yaml` is rewritten).
pub const FLUSH_EVERY: Duration = Duration::from_secs(1);
/// The ROS 2 distribution whose message definitions and type hashes the bag carries.
pub const ROS_DISTRO: &str = "jazzy";
/// rosbag2's metadata version (ROS 2 Jazzy and Kilted).
pub const METADATA_VERSION: u32 = 9;

/// An MCAP footer with no summary (summary start 0, summary offset start 0, CRC 0) and the
/// closing magic: what ends the file between flushes.
const OPEN_FOOTER: [u8; 37] = {
    let mut f = [0u8; 37];
    f[0] = 0x02; // Footer
    f[1] = 20; // record length, u64 LE
    let magic = *b"\x89MCAP0\r\n";
    let mut i = 0;
    while i < 8 {
        f[29 + i] = magic[i];
        i += 1;
    }
    f
};

/// The file under the MCAP writer: writes reach it only on flush, as one positioned write of
/// the pending bytes followed by [`OPEN_FOOTER`] (while `open` is set), which the next flush
/// overwrites.
struct TrailedFile {
    file: File,
    /// Bytes of the MCAP stream in the file (the footer after them is not counted).
    written: u64,
    pending: Vec<u8>,
    open: Arc<AtomicBool>,
}

impl Write for TrailedFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.pending.extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let open = self.open.load(Ordering::Relaxed);
        if self.pending.is_empty() && !open {
            return Ok(());
        }
        let n = self.pending.len() as u64;
        if open {
            self.pending.extend_from_slice(&OPEN_FOOTER);
        }
        self.file.write_all_at(&self.pending, self.written)?;
        self.written += n;
        self.pending.clear();
        Ok(())
    }
}

impl Seek for TrailedFile {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        let here = self.written + self.pending.len() as u64;
        match pos {
            SeekFrom::Current(0) => Ok(here),
            SeekFrom::Start(p) if p == here => Ok(here),
            _ => Err(std::io::Error::new(
                std::io::ErrorKind::Unsupported,
                "the bag's file is written front to back",
            )),
        }
    }
}

/// One topic of the bag.
struct Topic {
    name: String,
    ros_type: &'static str,
    hash: String,
    channel: u16,
    count: u64,
}

/// A topic's handle, from `Bag::topic` ([`Recorder::topic`](super::Recorder::topic)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TopicId(usize);

/// A rosbag2 directory being written.
pub(super) struct Bag {
    dir: PathBuf,
    file_name: String,
    mcap: mcap::Writer<TrailedFile>,
    open: Arc<AtomicBool>,
    topics: Vec<Topic>,
    schemas: BTreeMap<&'static str, u16>,
    cdr: CdrWriter,
    first_ns: Option<u64>,
    last_ns: u64,
    messages: u64,
    last_flush: Instant,
    custom: Vec<(String, String)>,
}

/// The QoS rosbag2 records for a publisher with ROS 2's default profile (keep last 10,
/// reliable, volatile, no deadline / lifespan / lease), as version 9 writes it: the YAML
/// sequence of one map, at `indent` spaces.
fn qos_yaml(indent: usize) -> String {
    let pad = " ".repeat(indent);
    let mut out = String::new();
    let time = |name: &str| format!("{pad}  {name}:\n{pad}    sec: 0\n{pad}    nsec: 0\n");
    let _ = write!(
        out,
        "{pad}- history: keep_last\n{pad}  depth: 10\n{pad}  reliability: reliable\n\
         {pad}  durability: volatile\n{}{}{pad}  liveliness: system_default\n{}\
         {pad}  avoid_ros_namespace_conventions: false\n",
        time("deadline"),
        time("lifespan"),
        time("liveliness_lease_duration"),
    );
    out
}

/// A YAML scalar: plain when it is safe to be, else double-quoted (JSON's escapes are YAML's).
fn scalar(s: &str) -> String {
    let plain = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "_/.-".contains(c))
        && !s.starts_with(['-', '.'])
        && s.parse::<f64>().is_err()
        && !matches!(
            s.to_ascii_lowercase().as_str(),
            "true" | "false" | "null" | "yes" | "no" | "on" | "off" | "y" | "n"
        );
    if plain {
        s.to_owned()
    } else {
        serde_json::to_string(s).unwrap_or_else(|_| "\"\"".to_owned())
    }
}

impl Bag {
    /// Creates the bag directory `dir` (which must not exist, or be empty) with its `.mcap`
    /// and a first `metadata.yaml`.
    pub(super) fn create(dir: &Path) -> Result<Bag, RecordError> {
        let io = |path: &Path, e: &dyn std::fmt::Display| RecordError::Create {
            path: path.to_owned(),
            reason: e.to_string(),
        };
        match std::fs::read_dir(dir) {
            Ok(mut entries) => {
                if entries.next().is_some() {
                    return Err(RecordError::NotEmpty {
                        dir: dir.to_owned(),
                    });
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                std::fs::create_dir_all(dir).map_err(|e| io(dir, &e))?;
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotADirectory => {
                return Err(RecordError::NotADirectory {
                    path: dir.to_owned(),
                });
            }
            Err(e) => return Err(io(dir, &e)),
        }
        let stem = dir.file_name().map_or_else(
            || "handstack".to_owned(),
            |n| n.to_string_lossy().into_owned(),
        );
        let file_name = format!("{stem}_0.mcap");
        let path = dir.join(&file_name);
        let file = File::create_new(&path).map_err(|e| io(&path, &e))?;
        let open = Arc::new(AtomicBool::new(true));
        let sink = TrailedFile {
            file,
            written: 0,
            pending: Vec::with_capacity(64 * 1024),
            open: Arc::clone(&open),
        };
        let mcap = mcap::WriteOptions::new()
            .profile("ros2")
            .compression(None)
            // Chunks are built in memory and reach the file whole (see the module docs).
            .disable_seeking(true)
            .create(sink)
            .map_err(|e| io(&path, &e))?;
        let mut bag = Bag {
            dir: dir.to_owned(),
            file_name,
            mcap,
            open,
            topics: Vec::new(),
            schemas: BTreeMap::new(),
            cdr: CdrWriter::with_capacity(256),
            first_ns: None,
            last_ns: 0,
            messages: 0,
            last_flush: Instant::now(),
            custom: Vec::new(),
        };
        bag.flush().map_err(|e| io(&path, &e))?;
        Ok(bag)
    }

    /// Adds `key: value` to the metadata's `custom_data`.
    pub(super) fn custom(&mut self, key: &str, value: &str) {
        self.custom.push((key.to_owned(), value.to_owned()));
    }

    /// The topic `name` of message type `M`, declared on first use.
    pub(super) fn topic<M: Message>(&mut self, name: &str) -> Result<TopicId, RecordError> {
        if let Some(i) = self.topics.iter().position(|t| t.name == name) {
            return Ok(TopicId(i));
        }
        let description = M::description();
        let schema = match self.schemas.get(M::NAME) {
            Some(id) => *id,
            None => {
                let text = hand_zenoh::msg::definition(&description);
                let id = self
                    .mcap
                    .add_schema(M::NAME, "ros2msg", text.as_bytes())
                    .map_err(|e| self.write_error(&e))?;
                self.schemas.insert(M::NAME, id);
                id
            }
        };
        let hash = type_hash(&description).to_string();
        let metadata = BTreeMap::from([
            ("offered_qos_profiles".to_owned(), qos_yaml(0)),
            ("topic_type_hash".to_owned(), hash.clone()),
        ]);
        let channel = self
            .mcap
            .add_channel(schema, name, "cdr", &metadata)
            .map_err(|e| self.write_error(&e))?;
        self.topics.push(Topic {
            name: name.to_owned(),
            ros_type: M::NAME,
            hash,
            channel,
            count: 0,
        });
        Ok(TopicId(self.topics.len() - 1))
    }

    /// Writes `msg` on `topic`, received at `t_ns` (ns since the Unix epoch); flushes when the
    /// last flush is [`FLUSH_EVERY`] old.
    pub(super) fn write<M: Message>(
        &mut self,
        topic: TopicId,
        t_ns: u64,
        msg: &M,
    ) -> Result<(), RecordError> {
        self.cdr.clear();
        msg.write(&mut self.cdr);
        let t = &mut self.topics[topic.0];
        let header = mcap::records::MessageHeader {
            channel_id: t.channel,
            sequence: u32::try_from(t.count).unwrap_or(u32::MAX),
            log_time: t_ns,
            publish_time: t_ns,
        };
        t.count += 1;
        let written = self
            .mcap
            .write_to_known_channel(&header, self.cdr.as_bytes());
        written.map_err(|e| self.write_error(&e))?;
        self.messages += 1;
        self.first_ns.get_or_insert(t_ns);
        self.last_ns = self.last_ns.max(t_ns);
        if self.last_flush.elapsed() >= FLUSH_EVERY {
            self.flush().map_err(|e| self.write_error(&e))?;
        }
        Ok(())
    }

    /// Ends the chunk being built: it reaches the file with an open footer after it, and
    /// `metadata.yaml` counts it.
    pub(super) fn flush(&mut self) -> Result<(), Box<dyn std::error::Error>> {
        self.mcap.flush()?;
        self.write_metadata_yaml()?;
        self.last_flush = Instant::now();
        Ok(())
    }

    /// Writes the summary, the footer and the final `metadata.yaml`; returns the messages
    /// written.
    pub(super) fn finish(&mut self) -> Result<u64, RecordError> {
        let record = mcap::records::Metadata {
            name: "rosbag2".to_owned(),
            metadata: BTreeMap::from([("serialized_metadata".to_owned(), self.metadata(0))]),
        };
        self.mcap
            .write_metadata(&record)
            .map_err(|e| self.write_error(&e))?;
        self.open.store(false, Ordering::Relaxed);
        self.mcap.finish().map_err(|e| self.write_error(&e))?;
        self.write_metadata_yaml()
            .map_err(|e| self.write_error(&e))?;
        Ok(self.messages)
    }

    fn write_error(&self, e: &dyn std::fmt::Display) -> RecordError {
        RecordError::Write {
            path: self.dir.clone(),
            reason: e.to_string(),
        }
    }

    fn write_metadata_yaml(&self) -> std::io::Result<()> {
        let mut text = String::from("rosbag2_bagfile_information:\n");
        text.push_str(&self.metadata(2));
        let tmp = self.dir.join(".metadata.yaml.tmp");
        std::fs::write(&tmp, text)?;
        std::fs::rename(&tmp, self.dir.join("metadata.yaml"))
    }

    /// The bag's metadata as rosbag2's `convert<BagMetadata>::encode` lays it out, at `indent`.
    fn metadata(&self, indent: usize) -> String {
        let p = " ".repeat(indent);
        let start = self.first_ns.unwrap_or(0);
        let duration = self.last_ns.saturating_sub(start);
        let mut y = String::new();
        let _ = writeln!(y, "{p}version: {METADATA_VERSION}");
        let _ = writeln!(y, "{p}storage_identifier: mcap");
        let _ = writeln!(y, "{p}duration:\n{p}  nanoseconds: {duration}");
        let _ = writeln!(
            y,
            "{p}starting_time:\n{p}  nanoseconds_since_epoch: {start}"
        );
        let _ = writeln!(y, "{p}message_count: {}", self.messages);
        if self.topics.is_empty() {
            let _ = writeln!(y, "{p}topics_with_message_count: []");
        } else {
            let _ = writeln!(y, "{p}topics_with_message_count:");
        }
        for t in &self.topics {
            let _ = writeln!(y, "{p}  - topic_metadata:");
            let _ = writeln!(y, "{p}      name: {}", scalar(&t.name));
            let _ = writeln!(y, "{p}      type: {}", t.ros_type);
            let _ = writeln!(y, "{p}      serialization_format: cdr");
            let _ = writeln!(y, "{p}      offered_qos_profiles:");
            y.push_str(&qos_yaml(indent + 8));
            let _ = writeln!(y, "{p}      type_description_hash: {}", t.hash);
            let _ = writeln!(y, "{p}    message_count: {}", t.count);
        }
        let _ = writeln!(y, "{p}compression_format: \"\"");
        let _ = writeln!(y, "{p}compression_mode: \"\"");
        let _ = writeln!(y, "{p}relative_file_paths:\n{p}  - {}", self.file_name);
        let _ = writeln!(y, "{p}files:\n{p}  - path: {}", self.file_name);
        let _ = writeln!(
            y,
            "{p}    starting_time:\n{p}      nanoseconds_since_epoch: {start}"
        );
        let _ = writeln!(y, "{p}    duration:\n{p}      nanoseconds: {duration}");
        let _ = writeln!(y, "{p}    message_count: {}", self.messages);
        if self.custom.is_empty() {
            let _ = writeln!(y, "{p}custom_data: ~");
        } else {
            let _ = writeln!(y, "{p}custom_data:");
            for (k, v) in &self.custom {
                let _ = writeln!(y, "{p}  {}: {}", scalar(k), scalar(v));
            }
        }
        let _ = writeln!(y, "{p}ros_distro: {ROS_DISTRO}");
        y
    }
}

#[cfg(test)]
mod tests {
    use super::{Bag, scalar};
    use hand_zenoh::msg::Message;
    use hand_zenoh::msg::handstack_msgs::PressureFrame;

    fn messages(path: &std::path::Path) -> Vec<(String, PressureFrame)> {
        let bytes = std::fs::read(path).expect("mcap");
        mcap::MessageStream::new(&bytes)
            .expect("magic")
            .map(|m| {
                let m = m.expect("a message");
                (
                    m.channel.topic.clone(),
                    PressureFrame::from_cdr(&m.data).expect("CDR"),
                )
            })
            .collect()
    }

    #[test]
    fn a_flushed_bag_reads_back_before_and_after_its_end() {
        let dir = std::env::temp_dir().join(format!("handstack-bag-unit-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut bag = Bag::create(&dir).expect("bag");
        let topic = bag
            .topic::<PressureFrame>("/hand0/tactile/raw")
            .expect("topic");
        let frame = |p: f32| PressureFrame {
            pressure_pa: vec![p; 3],
            ..PressureFrame::default()
        };
        for (k, p) in [1.0, 2.0, 3.0].into_iter().enumerate() {
            bag.write(topic, 1_000 + k as u64, &frame(p))
                .expect("write");
        }
        let file = dir.join(format!(
            "{}_0.mcap",
            dir.file_name().unwrap().to_string_lossy()
        ));
        // Not flushed yet: the file holds the header and an open footer, no message.
        assert!(messages(&file).is_empty());
        bag.flush().expect("flush");
        // Flushed, not finished (a run killed here): all three, behind an open footer.
        let read = messages(&file);
        assert_eq!(read.len(), 3);
        assert_eq!(read[2].1, frame(3.0));
        assert!(
            std::fs::read_to_string(dir.join("metadata.yaml"))
                .unwrap()
                .contains("message_count: 3")
        );
        bag.write(topic, 2_000, &frame(4.0)).expect("write");
        assert_eq!(bag.finish().expect("finish"), 4);
        assert_eq!(messages(&file).len(), 4);
        let bytes = std::fs::read(&file).unwrap();
        let summary = mcap::Summary::read(&bytes)
            .expect("summary")
            .expect("a summary");
        assert_eq!(summary.stats.expect("stats").message_count, 4);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn yaml_scalars_are_quoted_when_they_must_be() {
        assert_eq!(scalar("/hand0/tactile/raw"), "/hand0/tactile/raw");
        assert_eq!(scalar(""), "\"\"");
        assert_eq!(scalar("1.5"), "\"1.5\"");
        assert_eq!(scalar("yes"), "\"yes\"");
        assert_eq!(scalar("a: b"), "\"a: b\"");
    }
}
