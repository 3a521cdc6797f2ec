#!/usr/bin/env python3
"""Independent ROS 2 / rmw_zenoh client for handstack, written without the Rust side's code.

Everything ROS-specific is derived here from the `.msg` files and rosbags' ROS 2 Jazzy type store
(type hashes, CDR), and everything Zenoh-specific from eclipse-zenoh and rmw_zenoh's own texts:
`docs/design.md` (key expressions, liveliness tokens, attachments), `attachment_helpers.cpp`
(attachment serialization) and `liveliness_utils.cpp` (entity GIDs). Subcommands: hashes, cdr,
encode, attachment, gid, subscribe, publish, call, serve, router, selftest. Every command prints one
JSON object (`encode`: one hex line); failures print {"error": ...} and exit 1. rosbags and
xxhash are imported lazily so that `router` runs under any eclipse-zenoh 1.x without them.
"""
from __future__ import annotations

import argparse
import contextlib
import dataclasses
import importlib.metadata
import json
import os
import queue
import select
import socket
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import zenoh
from zenoh.ext import Int64, ZDeserializeError, z_deserialize, z_serialize

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore

DEFAULT_MSGS = Path(__file__).resolve().parents[2] / "crates/hand-zenoh/ros/handstack_msgs/msg"
STD_MSGS = ("sensor_msgs/msg/Imu", "sensor_msgs/msg/JointState", "sensor_msgs/msg/ChannelFloat32",
            "geometry_msgs/msg/WrenchStamped",
            "geometry_msgs/msg/PoseStamped", "std_msgs/msg/Header", "builtin_interfaces/msg/Time")
# Services as (request fields, response fields); rosbags' stores carry no services at all.
SERVICES = {"std_srvs/srv/Trigger": ("", "bool success\nstring message"),
            "std_srvs/srv/SetBool": ("bool data", "bool success\nstring message"),
            "example_interfaces/srv/AddTwoInts": ("int64 a\nint64 b", "int64 sum")}
HASHED = STD_MSGS + ("std_srvs/srv/Trigger",)
# Hashes published outside rosbags, checked by `selftest` (sources in README.md).
PUBLISHED = {
    "std_msgs/msg/String": "df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18",
    "example_interfaces/srv/AddTwoInts": "e118de6bf5eeb66a2491b5bda11202e7b68f198d6f67922cf30364858239c81a",
    "std_srvs/srv/Trigger": "eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f",
    "std_srvs/srv/SetBool": "abe9e4bb6b41b40e6789712c00ec8871923e089af3f667a79992a428cff2da0a",
    "std_srvs/srv/SetBool_Request": "c62fbb99d94e1b25e8ef9e109f9581956bb1b3361a45a4e5810c36a90d29932e",
    "std_srvs/srv/SetBool_Response": "d0814e7f7b4880ab77e9c57426c7aa1562ab69f11eef8e2e968812f9cbd0b059",
    "std_srvs/srv/SetBool_Event": "3c4c20015afb4303eafd347b1d6a786f171a89c814726961a9593ef10df878cf",
    "service_msgs/msg/ServiceEventInfo": "41bcbbe07a75c9b52bc96bfd5c24d7f0fc0a08c0cb7921b3373c5732345a6f45",
    "sensor_msgs/msg/Imu": "7d9a00ff131080897a5ec7e26e315954b8eae3353c3f995c55faf71574000b5b",
}
HUMBLE_HASH = "TypeHashNotSupported"
PUB_QOS = "::,7:,:,:,,"  # rmw_zenoh's token QoS field for a default publisher (design.md talker)
SUB_QOS = "::,10:,:,:,,"  # ... and for a default subscription / service (design.md listener)
NODE = "handstack_interop"
SELFTEST_TOPIC, SELFTEST_TYPE, SELFTEST_SERVICE = "/hand0/tactile/raw", "handstack_msgs/msg/PressureFrame", \
    "/hand0/tactile/tare"
SELFTEST_COMMAND, SELFTEST_COMMAND_TYPE = "/hand0/gripper/command", "handstack_msgs/msg/GripperCommand"
GID_LEN = 16  # RMW_GID_STORAGE_SIZE
ATTACHMENT_LEN = 8 + 8 + 1 + GID_LEN  # design.md: i64 LE, i64 LE, 1-byte GID length, GID = 33 bytes
LEGACY_PREFIX = bytes([15]) + b"sequence_number"  # how the old keyed attachment starts
# rmw_zenoh <= 0.2.3: three keyed fields, each key a length-prefixed string, the GID a counted sequence.
LEGACY_LEN = len(LEGACY_PREFIX) + 8 + 1 + len("source_timestamp") + 8 + 1 + len("source_gid") + 1 + GID_LEN
MAX_COUNT = 100_000  # upper bound on samples taken or published by one run


class Failure(Exception):
    """A run that did not complete; `info` holds what was measured before it stopped."""

    def __init__(self, message: str, **info: Any) -> None:
        super().__init__(message)
        self.info = info


# ---------------------------------------------------------------- types, hashes, CDR (rosbags)
def map_desc(desc: Any, fn: Any) -> Any:
    """Apply `fn` to the leaf (BASE or NAME) of a rosbags field descriptor, through arrays/sequences."""
    from rosbags.typesys.base import Nodetype
    if desc[0] in (Nodetype.ARRAY, Nodetype.SEQUENCE):
        return (desc[0], (map_desc(desc[1][0], fn), desc[1][1]))
    return fn(desc)


def service_types(name: str, request: str, response: str) -> dict[str, Any]:
    """Type description pieces of service `name` (REP 2011), as rosbags message fielddefs."""
    from rosbags.typesys import get_types_from_msg
    from rosbags.typesys.base import Nodetype
    pkg = name.split("/")[0]
    event = f"service_msgs/ServiceEventInfo info\n{name}_Request[<=1] request\n{name}_Response[<=1] response"
    top = f"{name}_Request request_message\n{name}_Response response_message\n{name}_Event event_message"
    types: dict[str, Any] = {}
    for suffix, text in (("_Request", request), ("_Response", response), ("_Event", event), ("", top)):
        types.update(get_types_from_msg(text, f"{name}{suffix}"))
    # rosbags files any non-msg/action name under "<pkg>/srv/msg/": put the pieces back under srv/.
    def fix(n: str) -> str:
        return n.replace(f"{pkg}/srv/msg/", f"{pkg}/srv/")
    return {fix(k): (c, [(f, map_desc(d, lambda t: (Nodetype.NAME, fix(t[1])) if t[0] == Nodetype.NAME else t))
                         for f, d in fs]) for k, (c, fs) in types.items()}


def load_typestore(msgs: Path) -> tuple[Typestore, list[str]]:
    """Jazzy store plus our package's `.msg` files (DIR or DIR/msg) and SERVICES; returns our names."""
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore
    store = get_typestore(Stores.ROS2_JAZZY)
    folder = msgs / "msg" if (msgs / "msg").is_dir() else msgs
    pkg = folder.parent.name
    types: dict[str, Any] = {}
    ours = [f"{pkg}/msg/{p.stem}" for p in sorted(folder.glob("*.msg"))]
    for name, path in zip(ours, sorted(folder.glob("*.msg"))):
        types.update(get_types_from_msg(path.read_text(), name))
    for name, (req, resp) in SERVICES.items():
        types.update(service_types(name, req, resp))
    store.register(types)
    return store, ours


def ros_hash(store: Typestore, name: str) -> str:
    """RIHS01 as rosidl computes it: rosbags' hash_rihs01 after rosidl's msg->IDL `char`->`uint8`.

    rosbags hashes a .msg `char` as FIELD_TYPE_CHAR (13); rosidl_adapter maps it to IDL uint8 (3)
    first. It matters for service_msgs/ServiceEventInfo (char[16] client_gid), so every service.
    """
    from rosbags.typesys.base import Nodetype
    def uint8(d: Any) -> Any:
        return (d[0], ("uint8", d[1][1])) if d[0] == Nodetype.BASE and d[1][0] == "char" else d
    saved = store.fielddefs
    store.fielddefs = {k: (c, [(f, map_desc(d, uint8)) for f, d in fs]) for k, (c, fs) in saved.items()}
    try:
        return store.hash_rihs01(name)
    finally:
        store.fielddefs = saved


def to_plain(value: Any) -> Any:
    """A rosbags message as JSON-ready data (numpy arrays as lists)."""
    if dataclasses.is_dataclass(value):
        return {f.name: to_plain(getattr(value, f.name)) for f in dataclasses.fields(value)
                if not f.name.startswith("__")}  # rosbags' __msgtype__ is a string-annotated ClassVar
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [to_plain(v) for v in value]
    return value


def from_plain(store: Typestore, name: str, data: dict[str, Any]) -> Any:
    """Build message `name` from JSON data; missing fields are zero / empty, unknown ones rejected."""
    import numpy as np
    from rosbags.typesys.base import Nodetype
    def field(desc: Any, v: Any) -> Any:
        if desc[0] == Nodetype.NAME:
            return from_plain(store, desc[1], v or {})
        if desc[0] == Nodetype.BASE:
            typ = desc[1][0]
            conv = {"string": str, "bool": bool, "float32": float, "float64": float}.get(typ, int)
            return conv(v) if v is not None else conv()
        (sub, size), seq = desc[1], desc[0] == Nodetype.SEQUENCE
        items = v if v is not None else ([] if seq else [None] * size)
        if sub[0] == Nodetype.BASE and sub[1][0] != "string":
            dtype = {"bool": "bool", "byte": "uint8", "char": "uint8"}.get(sub[1][0], sub[1][0])
            return np.array([field(sub, x) for x in items], dtype=dtype)
        return [field(sub, x) for x in items]
    fields = store.fielddefs[name][1]
    if unknown := set(data) - {f for f, _ in fields} - {"structure_needs_at_least_one_member"}:
        raise ValueError(f"{name} has no field(s) {sorted(unknown)}")
    return store.types[name](**{f: field(d, data.get(f)) for f, d in fields})


def encode(store: Typestore, name: str, msg: Any) -> bytes:
    """CDR little-endian with its 4-byte encapsulation header, as rmw_zenoh payloads are."""
    return bytes(store.serialize_cdr(msg, name, little_endian=True))


def roundtrip(store: Typestore, name: str, raw: bytes) -> tuple[Any, bool]:
    """Decode `raw` as `name` and report whether re-encoding gives the same bytes."""
    msg = store.deserialize_cdr(raw, name)
    return msg, encode(store, name, msg) == raw


# ---------------------------------------------------------------- rmw_zenoh conventions (zenoh)
def dds_name(name: str) -> str:
    """`pkg/msg/Name` -> `pkg::msg::dds_::Name_` (services: `pkg::srv::dds_::Name_`)."""
    pkg, kind, base = name.split("/")
    return f"{pkg}::{kind}::dds_::{base}_"


def data_key(domain: int, topic: str, name: str, hash_: str) -> str:
    """Topic / service key expression: `<domain>/<name without outer '/'>/<dds type>/<hash>`."""
    return f"{domain}/{topic.strip('/')}/{dds_name(name)}/{hash_}"


def node_token(domain: int, zid: str, node: str = NODE) -> str:
    """Liveliness token of a node (node id 0, empty enclave and namespace: '%'), design.md."""
    return f"@ros2_lv/{domain}/{zid}/0/0/NN/%/%/{node}"


def entity_token(domain: int, zid: str, eid: int, kind: str, topic: str, name: str, hash_: str,
                 qos: str, node: str = NODE) -> str:
    """Liveliness token of an entity of `node` (node id 0, empty enclave and namespace: '%')."""
    mangled = topic.replace("/", "%")
    return f"@ros2_lv/{domain}/{zid}/0/{eid}/{kind}/%/%/{node}/{mangled}/{dds_name(name)}/{hash_}/{qos}"


def entity_gid(token: str) -> bytes:
    """An entity's GID as rmw_zenoh computes it (`liveliness_utils.cpp`, `Entity` constructor).

    XXH3-128 of the entity's whole liveliness key expression; the 16 GID bytes are the hash's
    low 64 bits then its high 64 bits, each memcpy'd from a little-endian machine, i.e. the
    128-bit hash as one little-endian number. Uses the `xxhash` package's XXH3, not ours.
    """
    import xxhash
    h = xxhash.xxh3_128_intdigest(token.encode())
    return (h & (2**64 - 1)).to_bytes(8, "little") + (h >> 64).to_bytes(8, "little")


# Attachments. Current layout (rmw_zenoh `docs/design.md`, rolling branch 2025, "Publishers" /
# "Service Clients" / "Service Servers"; `rmw_zenoh_cpp/src/detail/attachment_helpers.cpp` in
# rmw_zenoh >= 0.2.4 on Jazzy, >= 0.1.2 on Humble, >= 0.6.0 on rolling): zenoh::ext::Serializer of
# (int64 sequence_number, int64 source_timestamp, std::array<uint8_t, 16> source_gid). In the
# Zenoh serialization format (eclipse-zenoh/roadmap rfcs/ALL/Serialization.md) integers are
# fixed-width little-endian and a fixed-size array is written like a sequence: LEB128 element
# count (16 = one byte 0x10), then the elements. So: <seq i64 LE> <stamp i64 LE> 10 <16 GID bytes>
# = 33 bytes. Python has no fixed-size array type; `bytes` serializes as a sequence of u8, which
# gives the same bytes.
def make_attachment(seq: int, stamp_ns: int, gid: bytes) -> bytes:
    """Current rmw_zenoh attachment, made with zenoh-ext's serializer: (i64, i64, 16 x u8)."""
    if len(gid) != GID_LEN:
        raise ValueError(f"a GID has {GID_LEN} bytes, not {len(gid)}")
    return z_serialize((Int64(seq), Int64(stamp_ns), bytes(gid))).to_bytes()


def manual_attachment(seq: int, stamp_ns: int, gid: bytes) -> bytes:
    """The same 33 bytes written out by hand from design.md's description (a check of the above)."""
    return struct.pack("<qqB", seq, stamp_ns, len(gid)) + bytes(gid)


def make_legacy_attachment(seq: int, stamp_ns: int, gid: bytes) -> bytes:
    """Old keyed layout (rmw_zenoh <= 0.2.3 on Jazzy, <= 0.1.1 on Humble): str, i64, str, i64, str, u8s."""
    if len(gid) != GID_LEN:
        raise ValueError(f"a GID has {GID_LEN} bytes, not {len(gid)}")
    return z_serialize(("sequence_number", Int64(seq), "source_timestamp", Int64(stamp_ns),
                        "source_gid", bytes(gid))).to_bytes()


def manual_legacy_attachment(seq: int, stamp_ns: int, gid: bytes) -> bytes:
    """The old 77 bytes by hand: each key as a one-byte LEB128 length + UTF-8 (all are < 128)."""
    return b"".join(bytes([len(k)]) + k.encode() + v for k, v in (
        ("sequence_number", struct.pack("<q", seq)), ("source_timestamp", struct.pack("<q", stamp_ns)),
        ("source_gid", bytes([len(gid)]) + bytes(gid))))


class AttachmentError(ValueError):
    """An attachment that is not exactly the current layout; `info` says what it looks like."""

    def __init__(self, raw: bytes | None, what: str) -> None:
        super().__init__(what)
        self.info = {"attachment_len": None if raw is None else len(raw),
                     "attachment_hex": None if raw is None else raw.hex(),
                     "looks_legacy": raw is not None and looks_legacy(raw)}


def parse_legacy_attachment(raw: bytes) -> tuple[int, int, bytes]:
    """(sequence_number, source_timestamp, gid) of an old keyed attachment; ValueError otherwise."""
    # Checked before zenoh-ext reads it: its deserializer allocates a string's or sequence's length
    # as read, and a current attachment's timestamp bytes there asked for 853 GB and aborted.
    if len(raw) != LEGACY_LEN or not raw.startswith(LEGACY_PREFIX):
        raise ValueError("not the old layout")
    tup = tuple[str, Int64, str, Int64, str, bytes]
    try:
        k1, seq, k2, stamp, k3, gid = z_deserialize(tup, zenoh.ZBytes(raw))
    except (ZDeserializeError, ValueError, TypeError, UnicodeDecodeError) as exc:
        raise ValueError(f"not the old layout: {exc}") from None
    if (k1, k2, k3) != ("sequence_number", "source_timestamp", "source_gid") or len(gid) != GID_LEN \
            or make_legacy_attachment(seq, stamp, gid) != raw:
        raise ValueError("not the old layout")
    return int(seq), int(stamp), bytes(gid)


def looks_legacy(raw: bytes) -> bool:
    """True for an exact old-layout (77-byte, keyed) attachment."""
    try:
        parse_legacy_attachment(raw)
    except ValueError:
        return False
    return True


def parse_attachment(raw: bytes | None) -> tuple[int, int, bytes]:
    """(sequence_number, source_timestamp, gid) of a current-layout attachment, else AttachmentError.

    zenoh-ext's deserializer reads (i64, i64, sequence of u8); the count must be 16, and the bytes
    must re-serialize to exactly `raw` (z_deserialize, like rmw_zenoh's reader, ignores trailing
    bytes; here they are an error).
    """
    if raw is None:
        raise AttachmentError(None, "no attachment")
    if looks_legacy(raw):
        raise AttachmentError(raw, f"attachment is the old keyed {len(raw)}-byte layout, not the "
                                   f"{ATTACHMENT_LEN}-byte one (rmw_zenoh <= 0.2.3 Jazzy / <= 0.1.1 Humble)")
    # Checked before zenoh-ext reads it (see `parse_legacy_attachment`).
    if len(raw) != ATTACHMENT_LEN or raw[16] != GID_LEN:
        raise AttachmentError(raw, f"attachment is {len(raw)} bytes, not the {ATTACHMENT_LEN}-byte layout")
    try:
        seq, stamp, gid = z_deserialize(tuple[Int64, Int64, bytes], zenoh.ZBytes(raw))
    except (ZDeserializeError, ValueError, TypeError) as exc:
        raise AttachmentError(raw, f"attachment does not deserialize as (i64, i64, u8 sequence): {exc}") from None
    if len(gid) != GID_LEN:
        raise AttachmentError(raw, f"attachment GID has {len(gid)} bytes, not {GID_LEN}")
    if len(raw) != ATTACHMENT_LEN or make_attachment(seq, stamp, gid) != raw:
        raise AttachmentError(raw, f"attachment is {len(raw)} bytes, not the {ATTACHMENT_LEN}-byte layout")
    return int(seq), int(stamp), bytes(gid)


def make_config(mode: str, connect: list[str], listen: list[str]) -> zenoh.Config:
    """Loopback-only session config: given endpoints, multicast scouting (UDP) off."""
    conf = {"mode": mode, "connect": {"endpoints": connect}, "listen": {"endpoints": listen},
            "scouting": {"multicast": {"enabled": False}}}
    return zenoh.Config.from_json5(json.dumps(conf))


def udp_sockets(pid: int | str = "self") -> int:
    """Number of UDP sockets process `pid` holds (from /proc)."""
    links = set()
    for fd in os.listdir(f"/proc/{pid}/fd"):
        with contextlib.suppress(OSError):  # an fd closed meanwhile
            links.add(os.readlink(f"/proc/{pid}/fd/{fd}"))
    rows = [line.split() for t in ("udp", "udp6") for line in Path(f"/proc/net/{t}").read_text().splitlines()[1:]]
    return sum(1 for r in rows if f"socket:[{r[9]}]" in links)


def wait_for_tokens(session: zenoh.Session, domain: int, wanted: list[tuple[str, str, str, str]],
                    deadline: float) -> list[str]:
    """Block until a liveliness token (kind, mangled name, dds type, hash) exists for each `wanted`.

    Returns every token seen that matches one of `wanted` (e.g. each publisher on a topic).
    """
    tokens: queue.Queue[str] = queue.Queue()
    def on_token(sample: zenoh.Sample) -> None:
        if sample.kind == zenoh.SampleKind.PUT:
            tokens.put(str(sample.key_expr))
    sub = session.liveliness().declare_subscriber(f"@ros2_lv/{domain}/**", on_token, history=True)
    missing, near, found, all_wanted = set(wanted), [], [], set(wanted)
    def take(key: str) -> None:
        p = key.split("/")
        if len(p) >= 13:
            kind = (p[5], p[9], p[10], p[11])
            if kind in all_wanted:
                found.append(key)
            missing.discard(kind)
            near.extend(key for w in missing if (w[0], w[1]) == (p[5], p[9]))
    try:
        while missing:
            try:
                key = tokens.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise Failure("discovery timed out", missing=sorted(missing), same_name_tokens=near) from None
            take(key)
        with contextlib.suppress(queue.Empty):  # tokens that arrived together with the last one
            while True:
                take(tokens.get_nowait())
    finally:
        sub.undeclare()
    return found


def hash_function(store: Typestore, humble: bool) -> Any:
    """Type name -> the hash field of keys and tokens (Humble's rmw_zenoh: TypeHashNotSupported)."""
    return (lambda n: HUMBLE_HASH) if humble else (lambda n: ros_hash(store, n))


# ---------------------------------------------------------------- subcommands
def cmd_hashes(args: argparse.Namespace) -> dict[str, str]:
    """RIHS01 of our messages, the standard messages we use and std_srvs/srv/Trigger."""
    store, ours = load_typestore(args.msgs)
    return {name: ros_hash(store, name) for name in [*ours, *HASHED]}


def cmd_cdr(args: argparse.Namespace) -> dict[str, Any]:
    """Decode CDR hex with rosbags, re-encode, compare."""
    store, _ = load_typestore(args.msgs)
    raw = bytes.fromhex(args.hex)
    msg, same = roundtrip(store, args.type, raw)
    out = {"roundtrip_identical": same, "fields": to_plain(msg)}
    return out if same else {**out, "reencoded_hex": encode(store, args.type, msg).hex()}


def cmd_encode(args: argparse.Namespace) -> str:
    """JSON fields -> CDR hex."""
    store, _ = load_typestore(args.msgs)
    return encode(store, args.type, from_plain(store, args.type, json.loads(args.json))).hex()


def cmd_attachment(args: argparse.Namespace) -> dict[str, str]:
    """Attachment bytes for --seq/--stamp/--gid via zenoh-ext (current layout; --legacy the old one),
    checked against the written-out layout and read back by this client's own parser."""
    gid = bytes.fromhex(args.gid)
    if len(gid) != GID_LEN:
        raise Failure(f"--gid needs {GID_LEN} bytes (32 hex digits), got {len(gid)}")
    make, manual = (make_legacy_attachment, manual_legacy_attachment) if args.legacy \
        else (make_attachment, manual_attachment)
    raw = make(args.seq, args.stamp, gid)
    if raw != manual(args.seq, args.stamp, gid):  # zenoh-ext and the written-out layout must agree
        raise Failure("zenoh-ext's bytes differ from the documented layout", hex=raw.hex(),
                      expected_hex=manual(args.seq, args.stamp, gid).hex())
    parse = parse_legacy_attachment if args.legacy else parse_attachment
    if parse(raw) != (args.seq, args.stamp, gid):
        raise Failure("the attachment does not read back", hex=raw.hex())
    return {"hex": raw.hex()}


def cmd_gid(args: argparse.Namespace) -> dict[str, str]:
    """GID of the entity with liveliness token --token: XXH3-128, low then high 64 bits, LE."""
    return {"gid_hex": entity_gid(args.token).hex()}


def cmd_subscribe(args: argparse.Namespace) -> dict[str, Any]:
    """Discover a publisher like rmw_zenoh does, take N samples, check them; optionally call a service."""
    store, _ = load_typestore(args.msgs)
    deadline, start, srv, stype = time.monotonic() + args.timeout, time.monotonic(), args.call_service, args.service_type
    hash_of = hash_function(store, args.humble)
    key = data_key(args.domain, args.topic, args.type, hash_of(args.type))
    wanted = [("MP", args.topic.replace("/", "%"), dds_name(args.type), hash_of(args.type))]
    wanted += [("SS", srv.replace("/", "%"), dds_name(stype), hash_of(stype))] if srv else []
    conf = make_config(args.mode, [args.connect], ["tcp/127.0.0.1:0"] if args.mode == "peer" else [])
    out: dict[str, Any] = {"key": key, "received": 0, "roundtrip_identical": 0, "attachment_ok": 0,
                           "attachment_len": None, "seq_first": None, "seq_last": None, "gaps": 0,
                           "seq_strictly_increasing": True, "gid_hex": None, "gid_matches_token": None,
                           "timestamps_monotonic": True, "first_fields": None, "service": None}
    with zenoh.open(conf) as session:
        zid, live = str(session.info.zid()), session.liveliness()
        client_token = entity_token(args.domain, zid, 11, "SC", srv, stype, hash_of(stype), SUB_QOS) if srv else None
        tokens = [live.declare_token(node_token(args.domain, zid)), live.declare_token(
            entity_token(args.domain, zid, 10, "MS", args.topic, args.type, hash_of(args.type), SUB_QOS))]
        if client_token:
            tokens.append(live.declare_token(client_token))
        samples: queue.Queue[zenoh.Sample] = queue.Queue()
        sub = session.declare_subscriber(key, samples.put)
        found = wait_for_tokens(session, args.domain, wanted, deadline)
        publisher_gids = {entity_gid(t).hex() for t in found if t.split("/")[5] == "MP"}
        out["discovery_s"], last_stamp = round(time.monotonic() - start, 3), 0
        while out["received"] < min(args.count, MAX_COUNT):
            try:
                sample = samples.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise Failure(f"timed out after {out['received']} of {args.count} samples", **out) from None
            raw = sample.payload.to_bytes()
            try:
                msg, same = roundtrip(store, args.type, raw)
            except Exception as exc:
                raise Failure(f"sample {out['received']} does not decode: {exc}", payload_hex=raw.hex(), **out) from None
            out["received"] += 1
            out["roundtrip_identical"] += same
            out["first_fields"] = out["first_fields"] or to_plain(msg)
            if not same and "first_mismatch" not in out:
                out["first_mismatch"] = {"got": raw.hex(), "reencoded": encode(store, args.type, msg).hex()}
            att = sample.attachment.to_bytes() if sample.attachment is not None else None
            try:
                seq, stamp, sgid = parse_attachment(att)
            except AttachmentError as exc:
                raise Failure(f"sample {out['received'] - 1}: {exc}", **{**out, **exc.info}) from None
            out["attachment_ok"] += 1
            out["attachment_len"] = len(att)
            if out["seq_last"] is not None:
                out["seq_strictly_increasing"] &= seq > out["seq_last"]
                out["gaps"] += max(0, seq - out["seq_last"] - 1)
                out["timestamps_monotonic"] &= stamp >= last_stamp
            out["seq_first"] = seq if out["seq_first"] is None else out["seq_first"]
            out["seq_last"], last_stamp, out["gid_hex"] = seq, stamp, out["gid_hex"] or sgid.hex()
            # Informational: does the GID follow rmw_zenoh's rule (XXH3-128 of a publisher's token)?
            out["gid_matches_token"] = (out["gid_matches_token"] is not False) and sgid.hex() in publisher_gids
        sub.undeclare()
        if srv:
            reply = request_reply(session, store, data_key(args.domain, srv, stype, hash_of(stype)),
                                  stype, {}, 1, entity_gid(client_token), deadline)
            out["service"] = {**reply.pop("response"), **reply}  # response fields at the top, as before
        out["udp_sockets"] = udp_sockets()
        for t in tokens:
            t.undeclare()
    if (out["roundtrip_identical"] < out["received"] or out["attachment_ok"] < out["received"]
            or not out["seq_strictly_increasing"] or not out["timestamps_monotonic"] or out["udp_sockets"]):
        raise Failure("received data failed a check", **out)
    return out


def request_reply(session: zenoh.Session, store: Typestore, key: str, name: str, fields: dict[str, Any],
                  seq: int, gid: bytes, deadline: float) -> dict[str, Any]:
    """One rmw_zenoh service call: get(ALL_COMPLETE, no consolidation) with request CDR and attachment.

    design.md "Service Clients": the attachment carries the request's sequence number, a source
    timestamp and the client's GID; "Service Servers": the reply's carries the same sequence
    number and client GID, with the server's own timestamp.
    """
    request = encode(store, f"{name}_Request", from_plain(store, f"{name}_Request", fields))
    replies = session.get(key, payload=request, attachment=make_attachment(seq, time.time_ns(), gid),
                          target=zenoh.QueryTarget.ALL_COMPLETE, consolidation=zenoh.ConsolidationMode.NONE,
                          timeout=max(0.1, deadline - time.monotonic()))
    for reply in replies:
        if reply.ok is None:
            raise Failure(f"service replied with an error: {reply.err.payload.to_string()}", key=key)
        msg, same = roundtrip(store, f"{name}_Response", reply.ok.payload.to_bytes())
        att = reply.ok.attachment.to_bytes() if reply.ok.attachment is not None else None
        try:
            rseq, _, rgid = parse_attachment(att)
        except AttachmentError as exc:
            raise Failure(f"service reply: {exc}", key=key, response=to_plain(msg),
                          **{**exc.info, "reply_attachment_len": exc.info["attachment_len"]}) from None
        return {"response": to_plain(msg), "key": key, "roundtrip_identical": same, "request_hex": request.hex(),
                "reply_attachment_len": len(att), "reply_seq": rseq,
                "seq_echoed": rseq == seq, "gid_echoed": rgid == gid}
    raise Failure("no service reply before the timeout", key=key)


def header_stamped(store: Typestore, name: str, fields: dict[str, Any]) -> bool:
    """True when `name` has a std_msgs/Header `header` whose stamp `fields` leaves unset."""
    from rosbags.typesys.base import Nodetype
    has = any(f == "header" and d[0] == Nodetype.NAME and d[1] == "std_msgs/msg/Header"
              for f, d in store.fielddefs[name][1])
    return has and "stamp" not in (fields.get("header") or {})


def endpoint(args: argparse.Namespace, name: str) -> tuple[Typestore, float, str, str]:
    """The type store, the run's deadline, `args.type`'s hash and the data key of `name`."""
    store, _ = load_typestore(args.msgs)
    hash_ = hash_function(store, args.humble)(args.type)
    return store, time.monotonic() + args.timeout, hash_, data_key(args.domain, name, args.type, hash_)


def cmd_publish(args: argparse.Namespace) -> dict[str, Any]:
    """Publish N samples like an rmw_zenoh publisher once a matching subscription is in the graph."""
    store, deadline, hash_, key = endpoint(args, args.topic)
    fields = json.loads(args.json)
    from_plain(store, args.type, fields)  # unknown fields fail before anything is declared
    stamp_now = header_stamped(store, args.type, fields)
    out: dict[str, Any] = {"key": key, "token": None, "gid_hex": None, "published": 0, "first_attachment_hex": None}
    with zenoh.open(make_config("peer", [args.connect], ["tcp/127.0.0.1:0"])) as s:
        zid, live = str(s.info.zid()), s.liveliness()
        token = entity_token(args.domain, zid, 10, "MP", args.topic, args.type, hash_, PUB_QOS)
        gid = entity_gid(token)
        out.update(token=token, gid_hex=gid.hex())
        pub = s.declare_publisher(key)
        tokens = [live.declare_token(node_token(args.domain, zid)), live.declare_token(token)]
        try:
            try:
                wait_for_tokens(s, args.domain, [("MS", args.topic.replace("/", "%"), dds_name(args.type), hash_)],
                                deadline)
            except Failure as exc:
                raise Failure(str(exc), **{**out, **exc.info}) from None
            # The token says a subscription exists; Zenoh's matching status says its subscriber
            # declaration has reached this session too, so the first sample is not lost.
            while not pub.matching_status.matching:
                if time.monotonic() >= deadline:
                    raise Failure("a subscription token appeared but no Zenoh subscriber matched", **out)
                time.sleep(0.01)
            start = time.monotonic()
            for seq in range(1, min(args.count, MAX_COUNT) + 1):
                due = start + (seq - 1) / args.rate
                if due > deadline:
                    raise Failure(f"timed out after {out['published']} of {args.count} samples", **out)
                time.sleep(max(0.0, due - time.monotonic()))
                now = time.time_ns()
                msg = dict(fields)
                if stamp_now:
                    msg["header"] = {**(fields.get("header") or {}),
                                     "stamp": {"sec": now // 10**9, "nanosec": now % 10**9}}
                att = make_attachment(seq, now, gid)
                pub.put(encode(store, args.type, from_plain(store, args.type, msg)), attachment=att)
                out["published"] = seq
                out["first_attachment_hex"] = out["first_attachment_hex"] or att.hex()
            # Let the last sample leave; with --linger, stay in the graph that long (a ROS 2
            # node that stops publishing but keeps running: its subscribers see no writer leave).
            time.sleep(max(0.0, min(max(0.2, args.linger), deadline - time.monotonic())))
        finally:
            for t in tokens:
                t.undeclare()
            pub.undeclare()
    return out


def cmd_call(args: argparse.Namespace) -> dict[str, Any]:
    """Call a service once like an rmw_zenoh client (SC token, attachment with --seq and own GID)."""
    store, deadline, hash_, key = endpoint(args, args.service)
    fields = json.loads(args.json)
    from_plain(store, f"{args.type}_Request", fields)  # unknown fields fail before anything is declared
    out: dict[str, Any] = {"key": key, "token": None, "gid_hex": None, "response": None,
                           "reply_attachment_len": None, "seq_echoed": False, "gid_echoed": False, "reply_seq": None}
    with zenoh.open(make_config("peer", [args.connect], ["tcp/127.0.0.1:0"])) as s:
        zid, live = str(s.info.zid()), s.liveliness()
        token = entity_token(args.domain, zid, 10, "SC", args.service, args.type, hash_, SUB_QOS)
        gid = entity_gid(token)
        out.update(token=token, gid_hex=gid.hex())
        tokens = [live.declare_token(node_token(args.domain, zid)), live.declare_token(token)]
        try:
            wait_for_tokens(s, args.domain, [("SS", args.service.replace("/", "%"), dds_name(args.type), hash_)],
                            deadline)
            reply = request_reply(s, store, key, args.type, fields, args.seq, gid, deadline)
        except Failure as exc:
            raise Failure(str(exc), **{**out, **exc.info}) from None
        finally:
            for t in tokens:
                t.undeclare()
    return {**out, **{k: reply[k] for k in ("response", "reply_attachment_len", "seq_echoed", "gid_echoed",
                                            "reply_seq", "roundtrip_identical")}}


REPLY_ATTACHMENTS = ("echo", "none", "next-seq", "other-gid")  # `serve --reply-attachment`: only "echo" is right


def reply_attachment(mode: str, seq: int, client_gid: bytes) -> bytes | None:
    """The reply's attachment: design.md's (request seq, server's timestamp, client GID), or a fault."""
    if mode == "none":
        return None
    if mode == "next-seq":
        seq += 1
    if mode == "other-gid":
        client_gid = bytes(b ^ 0xFF for b in client_gid)
    return make_attachment(seq, time.time_ns(), client_gid)


def cmd_serve(args: argparse.Namespace) -> dict[str, Any]:
    """Serve a service like an rmw_zenoh server (SS token, replies echo seq and client GID), N requests."""
    store, deadline, hash_, key = endpoint(args, args.service)
    name, fields = args.type, json.loads(args.json)
    response = encode(store, f"{name}_Response", from_plain(store, f"{name}_Response", fields))
    count, lock, done = min(args.count, MAX_COUNT), threading.Lock(), threading.Event()
    out: dict[str, Any] = {"key": key, "token": None, "reply_attachment": args.reply_attachment,
                           "served": 0, "refused": [], "extra": 0, "requests": []}
    client_tokens: set[str] = set()  # SC tokens of this service seen in the graph
    mangled = args.service.replace("/", "%")

    def on_token(sample: zenoh.Sample) -> None:
        p = str(sample.key_expr).split("/")
        if sample.kind == zenoh.SampleKind.PUT and len(p) >= 13 and (p[5], p[9]) == ("SC", mangled):
            with lock:
                client_tokens.add(str(sample.key_expr))

    def on_query(q: zenoh.Query) -> None:
        """design.md "Service Servers": read the request's attachment, reply with the response and
        an attachment carrying the request's sequence number and the client's GID."""
        with lock:
            if len(out["requests"]) + len(out["refused"]) >= count:
                out["extra"] += 1
                q.reply_err(f"this server answers {count} request(s)")
                return
            raw = q.attachment.to_bytes() if q.attachment is not None else None
            try:
                seq, stamp, client_gid = parse_attachment(raw)
            except AttachmentError as exc:
                out["refused"].append({"why": str(exc), **exc.info})
                q.reply_err(f"request attachment: {exc}")
            else:
                payload = q.payload.to_bytes() if q.payload is not None else b""
                try:
                    same = roundtrip(store, f"{name}_Request", payload)[1]
                except Exception as exc:  # noqa: BLE001 - a request that does not decode gets an error reply
                    out["refused"].append({"why": f"request does not decode: {exc}", "payload_hex": payload.hex()})
                    q.reply_err(f"bad request: {exc}")
                else:
                    att = reply_attachment(args.reply_attachment, seq, client_gid)
                    q.reply(q.key_expr, response, attachment=att)
                    out["requests"].append({"seq": seq, "client_gid_hex": client_gid.hex(), "stamp": stamp,
                                            "request_roundtrip_identical": same,
                                            "reply_attachment_hex": None if att is None else att.hex()})
            if len(out["requests"]) + len(out["refused"]) >= count:
                done.set()

    with zenoh.open(make_config("peer", [args.connect], ["tcp/127.0.0.1:0"])) as s:
        zid, live = str(s.info.zid()), s.liveliness()
        token = entity_token(args.domain, zid, 10, "SS", args.service, name, hash_, SUB_QOS)
        out["token"] = token
        graph = live.declare_subscriber(f"@ros2_lv/{args.domain}/**", on_token, history=True)
        # The queryable before the token: a client that sees the token can reach the server.
        queryable = s.declare_queryable(key, on_query, complete=True)
        tokens = [live.declare_token(node_token(args.domain, zid)), live.declare_token(token)]
        try:
            finished = done.wait(max(0.0, deadline - time.monotonic()))
            time.sleep(0.2)  # let the last reply leave before the session closes
        finally:
            for t in tokens:
                t.undeclare()
            queryable.undeclare()
            graph.undeclare()
        with lock:  # a copy, no longer shared with the callbacks
            gids = {entity_gid(t).hex() for t in client_tokens}
            # Informational: is each client GID rmw_zenoh's (XXH3-128 of an SC token of this service)?
            requests = [{**r, "client_gid_matches_token": r["client_gid_hex"] in gids} for r in out["requests"]]
            result = {**out, "served": len(requests), "refused": list(out["refused"]), "requests": requests}
    if not finished:
        raise Failure(f"timed out after {len(result['requests']) + len(result['refused'])} of {count} requests",
                      **result)
    return result


def cmd_router(args: argparse.Namespace) -> None:
    """A Zenoh router on one endpoint until `--seconds` pass or stdin closes."""
    deadline = time.monotonic() + args.seconds
    with zenoh.open(make_config("router", [], [args.listen])):
        print(json.dumps({"router": "ready", "listen": args.listen,
                          "zenoh": importlib.metadata.version("eclipse-zenoh")}), flush=True)
        while (left := deadline - time.monotonic()) > 0:
            if select.select([sys.stdin], [], [], left)[0] and not sys.stdin.readline():
                break


def mimic_node(store: Typestore, connect: str, humble: bool, stop: threading.Event,
               ready: threading.Event, inbox: list[tuple[bytes, bytes | None]]) -> None:
    """Selftest stand-in for an rmw_zenoh node, current attachment layout on every message.

    Publishes /hand0/tactile/raw at 100 Hz (GID: XXH3-128 of its MP token), serves
    /hand0/tactile/tare (the reply echoes the request's sequence number and client GID) and
    subscribes to /hand0/gripper/command, appending (payload, attachment) to `inbox`.
    """
    topic, tname, srv, sname = SELFTEST_TOPIC, SELFTEST_TYPE, SELFTEST_SERVICE, "std_srvs/srv/Trigger"
    hash_of = hash_function(store, humble)
    with zenoh.open(make_config("peer", [connect], ["tcp/127.0.0.1:0"])) as s:
        zid, live = str(s.info.zid()), s.liveliness()
        pub_token = entity_token(0, zid, 10, "MP", topic, tname, hash_of(tname), PUB_QOS, "mimic")
        gid = entity_gid(pub_token)

        def on_query(q: zenoh.Query) -> None:
            try:
                seq, _, client_gid = parse_attachment(q.attachment.to_bytes() if q.attachment is not None else None)
                store.deserialize_cdr(q.payload.to_bytes(), f"{sname}_Request")
            except Exception as exc:  # noqa: BLE001 - a bad request gets an error reply
                q.reply_err(f"bad request: {exc}")
                return
            resp = from_plain(store, f"{sname}_Response", {"success": True, "message": "tared 3 sensors"})
            q.reply(q.key_expr, encode(store, f"{sname}_Response", resp),
                    attachment=make_attachment(seq, time.time_ns(), client_gid))

        def on_command(sample: zenoh.Sample) -> None:
            if len(inbox) < 1000:
                att = sample.attachment
                inbox.append((sample.payload.to_bytes(), att.to_bytes() if att is not None else None))
        ctype = SELFTEST_COMMAND_TYPE
        entities = (s.declare_queryable(data_key(0, srv, sname, hash_of(sname)), on_query, complete=True),
                    s.declare_subscriber(data_key(0, SELFTEST_COMMAND, ctype, hash_of(ctype)), on_command),
                    live.declare_token(node_token(0, zid, "mimic")), live.declare_token(pub_token),
                    live.declare_token(entity_token(0, zid, 11, "SS", srv, sname, hash_of(sname), SUB_QOS, "mimic")),
                    live.declare_token(entity_token(0, zid, 12, "MS", SELFTEST_COMMAND, ctype, hash_of(ctype),
                                                    SUB_QOS, "mimic")))
        pub, seq = s.declare_publisher(data_key(0, topic, tname, hash_of(tname))), 0
        ready.set()
        while not stop.wait(0.01):  # the publishing period, not a wait for discovery
            seq, now = seq + 1, time.time_ns()
            frame = {"header": {"stamp": {"sec": now // 10**9, "nanosec": now % 10**9}, "frame_id": "hand0"},
                     "pressure_pa": [101325.0 + seq, 0.1 * seq, -3.5]}
            pub.put(encode(store, tname, from_plain(store, tname, frame)), attachment=make_attachment(seq, now, gid))
        pub.undeclare()
        for e in reversed(entities):
            e.undeclare()


def check_inbox(store: Typestore, inbox: list[tuple[bytes, bytes | None]], sent: dict[str, Any]) -> dict[str, Any]:
    """What the mimic subscription got from `publish`, checked against the spec and `sent`."""
    seqs, stamps, gids, same, errors = [], [], set(), 0, []
    for payload, att in inbox:
        same += roundtrip(store, SELFTEST_COMMAND_TYPE, payload)[1]
        try:
            seq, stamp, gid = parse_attachment(att)
        except AttachmentError as exc:
            errors.append(exc.info)
            continue
        seqs.append(seq)
        stamps.append(stamp)
        gids.add(gid.hex())
    expected_gid = entity_gid(sent["token"]).hex() if sent.get("token") else None
    return {"received": len(inbox), "roundtrip_identical": same, "attachment_errors": errors,
            "seqs": seqs, "seqs_are_1_to_n": seqs == list(range(1, sent["published"] + 1)),
            "timestamps_monotonic": stamps == sorted(stamps),
            "gid_is_xxh3_of_token": gids == {sent["gid_hex"]} and sent["gid_hex"] == expected_gid,
            "first_attachment_matches": bool(inbox) and inbox[0][1] is not None
            and inbox[0][1].hex() == sent["first_attachment_hex"]}


def serve_and_call(common: dict[str, Any]) -> dict[str, Any]:
    """Selftest of `serve`: it answers `call` (sequence number 43) on a service of its own."""
    served: list[dict[str, Any]] = []
    def serve() -> None:
        with contextlib.suppress(Failure):  # a timeout shows as no summary
            served.append(cmd_serve(argparse.Namespace(
                **common, service=SELFTEST_SERVICE + "_served", type="std_srvs/srv/Trigger",
                json=json.dumps({"success": True, "message": "served"}), count=1, reply_attachment="echo",
                timeout=15)))
    server = threading.Thread(target=serve)
    server.start()
    try:
        call = cmd_call(argparse.Namespace(**common, service=SELFTEST_SERVICE + "_served",
                                           type="std_srvs/srv/Trigger", json="{}", seq=43, timeout=15))
    finally:
        server.join()
    return {"call": call, "served": served[0] if served else None}


def cmd_selftest(args: argparse.Namespace) -> dict[str, Any]:
    """Hashes, attachment layouts, GIDs, then router + mimic node + subscribe / publish / call / serve."""
    store, ours = load_typestore(args.msgs)
    wrong = {n: ros_hash(store, n) for n, h in PUBLISHED.items() if ros_hash(store, n) != f"RIHS01_{h}"}
    gid = bytes(range(16))
    current = make_attachment(7, -1, gid)
    legacy = make_legacy_attachment(7, -1, gid)
    rejected = {}
    # An old attachment whose sequence number's low byte is 16 reads as (i64, i64, 16 bytes) + 44
    # trailing bytes; only the length check rejects it.
    for name, raw in (("legacy", legacy), ("legacy_seq16", make_legacy_attachment(16, -1, gid)),
                      ("trailing_byte", current + b"\0"), ("short_gid", current[:16] + b"\x0f" + gid[:15]),
                      ("empty", b""), ("none", None)):
        try:
            parse_attachment(raw)
            rejected[name] = False
        except AttachmentError as exc:
            rejected[name] = exc.info["looks_legacy"] if name.startswith("legacy") else True
    import xxhash
    checks: dict[str, Any] = {
        "published_hashes_match": not wrong, "mismatched": wrong,
        "attachment_layout": current == manual_attachment(7, -1, gid) and len(current) == ATTACHMENT_LEN
        and parse_attachment(current) == (7, -1, gid),
        "legacy_layout": legacy == manual_legacy_attachment(7, -1, gid) and len(legacy) == 77
        and legacy.startswith(LEGACY_PREFIX) and parse_legacy_attachment(legacy) == (7, -1, gid),
        "attachments_rejected": rejected,
        # XXH3-128 of "" from the xxHash reference (high64 99aa06d3014798d8, low64 6001c324468d497f),
        # and the GID byte order: the low half's LE bytes first.
        "xxh3_reference": xxhash.xxh3_128_hexdigest(b"") == "99aa06d3014798d86001c324468d497f"
        and entity_gid("").hex() == "7f498d4624c30160d8984701d306aa99",
        "design_md_talker_gid": entity_gid("@ros2_lv/2/8b20917502ee955ac4476e0266340d5c/0/10/MP/%/%/talker/"
                                           "%chatter/std_msgs::msg::dds_::String_/RIHS01_" + PUBLISHED[
                                               "std_msgs/msg/String"] + "/" + PUB_QOS).hex(),
        "default_roundtrips": all(roundtrip(store, n, encode(store, n, from_plain(store, n, {})))[1]
                                  for n in [*ours, *HASHED[:-1], "std_srvs/srv/Trigger_Request"])}
    with socket.socket() as probe:  # a free loopback port for the router
        probe.bind(("127.0.0.1", 0))
        endpoint = f"tcp/127.0.0.1:{probe.getsockname()[1]}"
    router = subprocess.Popen([sys.executable, __file__, "router", "--listen", endpoint, "--seconds", "180"],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        if not select.select([router.stdout], [], [], 10)[0] or "ready" not in router.stdout.readline():
            raise Failure("router did not start", endpoint=endpoint)
        checks["router_udp_sockets"] = udp_sockets(router.pid)
        for humble in (False, True):
            stop, ready, inbox = threading.Event(), threading.Event(), []
            node = threading.Thread(target=mimic_node, args=(store, endpoint, humble, stop, ready, inbox))
            node.start()
            run: dict[str, Any] = {}
            checks["humble" if humble else "hashed"] = run
            try:
                ready.wait(10)
                common = {"msgs": args.msgs, "connect": endpoint, "domain": 0, "humble": humble}
                run["subscribe"] = cmd_subscribe(argparse.Namespace(
                    **common, mode="peer", count=20, timeout=15, topic=SELFTEST_TOPIC, type=SELFTEST_TYPE,
                    call_service=SELFTEST_SERVICE, service_type="std_srvs/srv/Trigger"))
                run["publish"] = cmd_publish(argparse.Namespace(
                    **common, topic=SELFTEST_COMMAND, type=SELFTEST_COMMAND_TYPE, count=10, rate=50.0, linger=0.0, timeout=15,
                    json=json.dumps({"header": {"frame_id": "hand0"}, "position_rad": 0.5, "effort": 0.25})))
                for _ in range(200):  # up to 2 s for the last samples to arrive
                    if len(inbox) >= run["publish"]["published"]:
                        break
                    time.sleep(0.01)
                run["publish_received"] = check_inbox(store, list(inbox), run["publish"])
                run["call"] = cmd_call(argparse.Namespace(
                    **common, service=SELFTEST_SERVICE, type="std_srvs/srv/Trigger", json="{}", seq=42, timeout=15))
                run["serve"] = serve_and_call(common)
            finally:
                stop.set()
                node.join()
    finally:
        router.stdin.close()
        router.wait(10)
    def run_ok(r: dict[str, Any]) -> bool:
        sub, got, call = r["subscribe"], r["publish_received"], r["call"]
        return (sub["received"] == 20 and not sub["gaps"] and sub["attachment_len"] == ATTACHMENT_LEN
                and sub["gid_matches_token"] is True
                and all(sub["service"][k] for k in ("success", "seq_echoed", "gid_echoed", "roundtrip_identical"))
                and r["publish"]["published"] == 10 and got["received"] == 10 and got["roundtrip_identical"] == 10
                and not got["attachment_errors"] and got["seqs_are_1_to_n"] and got["timestamps_monotonic"]
                and got["gid_is_xxh3_of_token"] and got["first_attachment_matches"]
                and call["response"]["success"] is True and call["seq_echoed"] and call["gid_echoed"]
                and call["reply_seq"] == 42 and call["reply_attachment_len"] == ATTACHMENT_LEN
                and call["gid_hex"] == entity_gid(call["token"]).hex()
                and serve_ok(r["serve"]))
    def serve_ok(r: dict[str, Any]) -> bool:
        call, served = r["call"], r["served"]
        return (call["response"] == {"success": True, "message": "served"} and call["seq_echoed"]
                and call["gid_echoed"] and served is not None and served["served"] == 1 and not served["refused"]
                and served["requests"][0]["seq"] == 43 and served["requests"][0]["client_gid_hex"] == call["gid_hex"]
                and served["requests"][0]["client_gid_matches_token"] is True)
    if wrong or not checks["attachment_layout"] or not checks["legacy_layout"] or not all(rejected.values()) \
            or not checks["xxh3_reference"] or not checks["default_roundtrips"] or checks["router_udp_sockets"] \
            or not all(run_ok(checks[k]) for k in ("hashed", "humble")):
        raise Failure("selftest failed", **checks)
    return checks


def main() -> int:
    """Parse arguments, run one subcommand, print its result; exit 1 with {"error": ...} on failure."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    commands = {"hashes": cmd_hashes, "cdr": cmd_cdr, "encode": cmd_encode, "attachment": cmd_attachment,
                "gid": cmd_gid, "subscribe": cmd_subscribe, "publish": cmd_publish, "call": cmd_call,
                "serve": cmd_serve, "router": cmd_router, "selftest": cmd_selftest}
    ps = {name: sub.add_parser(name, help=fn.__doc__.splitlines()[0]) for name, fn in commands.items()}
    for name in ("hashes", "cdr", "encode", "subscribe", "publish", "call", "serve", "selftest"):
        ps[name].add_argument("--msgs", type=Path, default=DEFAULT_MSGS, help="handstack_msgs or its msg/ folder")
    for name, extra in (("cdr", "--hex"), ("encode", "--json")):
        ps[name].add_argument("--type", required=True)
        ps[name].add_argument(extra, required=True)
    p = ps["attachment"]
    p.add_argument("--seq", type=int, required=True, help="sequence number (int64)")
    p.add_argument("--stamp", type=int, required=True, help="source timestamp, ns since the UNIX epoch (int64)")
    p.add_argument("--gid", required=True, help="16-byte GID as 32 hex digits")
    p.add_argument("--legacy", action="store_true", help="the old keyed 77-byte layout")
    ps["gid"].add_argument("--token", required=True, help="an entity's full liveliness key expression")

    def positive(kind: type) -> Any:
        def parse(text: str) -> Any:
            value = kind(text)
            if value <= 0:
                raise argparse.ArgumentTypeError(f"must be > 0, got {text}")
            return value
        return parse
    for name in ("subscribe", "publish", "call", "serve"):
        p = ps[name]
        p.add_argument("--connect", required=True)
        p.add_argument("--domain", type=int, default=0)
        p.add_argument("--timeout", type=positive(float), default=10.0, help="seconds for the whole run")
        p.add_argument("--humble", action="store_true", help="keys and tokens carry TypeHashNotSupported")
    for name in ("subscribe", "publish"):
        ps[name].add_argument("--topic", default=SELFTEST_TOPIC if name == "subscribe" else SELFTEST_COMMAND)
        ps[name].add_argument("--type", default=SELFTEST_TYPE if name == "subscribe" else SELFTEST_COMMAND_TYPE)
        ps[name].add_argument("--count", type=positive(int), default=10)
    p = ps["subscribe"]
    p.add_argument("--mode", choices=("peer", "client"), default="peer")
    p.add_argument("--call-service", help="e.g. /hand0/tactile/tare")
    p.add_argument("--service-type", default="std_srvs/srv/Trigger")
    p = ps["publish"]
    p.add_argument("--json", default="{}", help="message fields; an unset header.stamp is each sample's time")
    p.add_argument("--rate", type=positive(float), default=10.0, help="samples per second")
    p.add_argument("--linger", type=float, default=0.0, help="seconds to stay after the last sample")
    p = ps["call"]
    p.add_argument("--service", default=SELFTEST_SERVICE)
    p.add_argument("--type", default="std_srvs/srv/Trigger", choices=sorted(SERVICES))
    p.add_argument("--json", default="{}", help="request fields")
    p.add_argument("--seq", type=int, default=1, help="the request's sequence number")
    p = ps["serve"]
    p.add_argument("--service", default=SELFTEST_SERVICE)
    p.add_argument("--type", default="std_srvs/srv/Trigger", choices=sorted(SERVICES))
    p.add_argument("--json", default='{"success": true, "message": "served"}', help="response fields")
    p.add_argument("--count", type=positive(int), default=1, help="requests to answer, then stop")
    p.add_argument("--reply-attachment", choices=REPLY_ATTACHMENTS, default="echo",
                   help="echo: design.md's; the others are faults, to test a client")
    ps["router"].add_argument("--listen", required=True)
    ps["router"].add_argument("--seconds", type=float, default=3600.0)
    args = ap.parse_args()
    try:
        result = commands[args.cmd](args)
    except Failure as exc:
        print(json.dumps({"error": str(exc), **exc.info}), flush=True)
        return 1
    except Exception as exc:  # noqa: BLE001 - every failure is reported as one JSON object
        print(json.dumps({"error": f"{type(exc).__name__}: {exc}"}), flush=True)
        return 1
    if result is not None:
        print(result if isinstance(result, str) else json.dumps(result, indent=2), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
