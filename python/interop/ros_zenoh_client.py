#!/usr/bin/env python3
"""Independent ROS 2 / rmw_zenoh client for handstack, written without the Rust side's code.

Everything ROS-specific is derived here from the `.msg` files and rosbags' ROS 2 Jazzy type store
(type hashes, CDR), and everything Zenoh-specific from eclipse-zenoh and the rmw_zenoh design
document (key expressions, liveliness tokens, attachment). Subcommands: hashes, cdr, encode,
subscribe, router, selftest. Every command prints one JSON object (`encode`: one hex line);
failures print {"error": ...} and exit 1. rosbags is imported lazily so that `router` runs
under any eclipse-zenoh 1.x without it.
"""
from __future__ import annotations

import argparse
import contextlib
import dataclasses
import importlib.metadata
import json
import os
import queue
import secrets
import select
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import zenoh
from zenoh.ext import Int64, UInt8, ZDeserializeError, z_deserialize, z_serialize

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore

DEFAULT_MSGS = Path(__file__).resolve().parents[2] / "crates/hand-zenoh/ros/handstack_msgs/msg"
STD_MSGS = ("sensor_msgs/msg/Imu", "sensor_msgs/msg/JointState", "geometry_msgs/msg/WrenchStamped",
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


def entity_token(domain: int, zid: str, eid: int, kind: str, topic: str, name: str, hash_: str,
                 qos: str, node: str = NODE) -> str:
    """Liveliness token of an entity of `node` (node id 0, empty enclave and namespace: '%')."""
    mangled = topic.replace("/", "%")
    return f"@ros2_lv/{domain}/{zid}/0/{eid}/{kind}/%/%/{node}/{mangled}/{dds_name(name)}/{hash_}/{qos}"


def make_attachment(seq: int, stamp_ns: int, gid: bytes) -> bytes:
    """rmw_zenoh attachment: zenoh-ext serialized (str, i64, str, i64, str, 16 x u8 sequence)."""
    return z_serialize(("sequence_number", Int64(seq), "source_timestamp", Int64(stamp_ns),
                        "source_gid", [UInt8(b) for b in gid])).to_bytes()


def parse_attachment(raw: bytes) -> tuple[int, int, bytes]:
    """(sequence_number, source_timestamp, gid); raises ValueError unless it re-serializes exactly."""
    tup = tuple[str, Int64, str, Int64, str, list[UInt8]]
    k1, seq, k2, stamp, k3, gid = z_deserialize(tup, zenoh.ZBytes(raw))
    if (k1, k2, k3) != ("sequence_number", "source_timestamp", "source_gid") or len(gid) != 16:
        raise ValueError(f"unexpected attachment layout {raw.hex()}")
    if make_attachment(seq, stamp, bytes(gid)) != raw:  # z_deserialize ignores trailing bytes
        raise ValueError(f"attachment has extra or non-canonical bytes: {raw.hex()}")
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
                    deadline: float) -> None:
    """Block until a liveliness token (kind, mangled name, dds type, hash) exists for each `wanted`."""
    tokens: queue.Queue[str] = queue.Queue()
    def on_token(sample: zenoh.Sample) -> None:
        if sample.kind == zenoh.SampleKind.PUT:
            tokens.put(str(sample.key_expr))
    sub = session.liveliness().declare_subscriber(f"@ros2_lv/{domain}/**", on_token, history=True)
    missing, near = set(wanted), []
    try:
        while missing:
            try:
                key = tokens.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                raise Failure("discovery timed out", missing=sorted(missing), same_name_tokens=near) from None
            p = key.split("/")
            if len(p) >= 13:
                missing.discard((p[5], p[9], p[10], p[11]))
                near += [key for w in missing if (w[0], w[1]) == (p[5], p[9])]
    finally:
        sub.undeclare()


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


def cmd_subscribe(args: argparse.Namespace) -> dict[str, Any]:
    """Discover a publisher like rmw_zenoh does, take N samples, check them; optionally call a service."""
    store, _ = load_typestore(args.msgs)
    deadline, start, srv, stype = time.monotonic() + args.timeout, time.monotonic(), args.call_service, args.service_type
    hash_of = (lambda n: HUMBLE_HASH) if args.humble else (lambda n: ros_hash(store, n))
    key = data_key(args.domain, args.topic, args.type, hash_of(args.type))
    wanted = [("MP", args.topic.replace("/", "%"), dds_name(args.type), hash_of(args.type))]
    wanted += [("SS", srv.replace("/", "%"), dds_name(stype), hash_of(stype))] if srv else []
    conf = make_config(args.mode, [args.connect], ["tcp/127.0.0.1:0"] if args.mode == "peer" else [])
    out: dict[str, Any] = {"key": key, "received": 0, "roundtrip_identical": 0, "attachment_ok": 0,
                           "seq_first": None, "seq_last": None, "gaps": 0, "seq_strictly_increasing": True,
                           "gid_hex": None, "timestamps_monotonic": True, "first_fields": None, "service": None}
    with zenoh.open(conf) as session:
        zid, gid, live = str(session.info.zid()), secrets.token_bytes(16), session.liveliness()
        tokens = [live.declare_token(f"@ros2_lv/{args.domain}/{zid}/0/0/NN/%/%/{NODE}"), live.declare_token(
            entity_token(args.domain, zid, 10, "MS", args.topic, args.type, hash_of(args.type), SUB_QOS))]
        if srv:
            tokens.append(live.declare_token(entity_token(args.domain, zid, 11, "SC", srv, stype, hash_of(stype),
                                                          SUB_QOS)))
        samples: queue.Queue[zenoh.Sample] = queue.Queue()
        sub = session.declare_subscriber(key, samples.put)
        wait_for_tokens(session, args.domain, wanted, deadline)
        out["discovery_s"], last_stamp = round(time.monotonic() - start, 3), 0
        while out["received"] < args.count:
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
            try:
                seq, stamp, sgid = parse_attachment(sample.attachment.to_bytes())
            except (AttributeError, ValueError, ZDeserializeError) as exc:
                out.setdefault("attachment_error", str(exc) or "no attachment")
                continue
            out["attachment_ok"] += 1
            if out["seq_last"] is not None:
                out["seq_strictly_increasing"] &= seq > out["seq_last"]
                out["gaps"] += max(0, seq - out["seq_last"] - 1)
                out["timestamps_monotonic"] &= stamp >= last_stamp
            out["seq_first"] = seq if out["seq_first"] is None else out["seq_first"]
            out["seq_last"], last_stamp, out["gid_hex"] = seq, stamp, out["gid_hex"] or sgid.hex()
        sub.undeclare()
        if srv:
            out["service"] = call_service(session, store, args, hash_of(stype), gid, deadline)
        out["udp_sockets"] = udp_sockets()
        del tokens
    if (out["roundtrip_identical"] < out["received"] or out["attachment_ok"] < out["received"]
            or not out["seq_strictly_increasing"] or not out["timestamps_monotonic"] or out["udp_sockets"]):
        raise Failure("received data failed a check", **out)
    return out


def call_service(session: zenoh.Session, store: Typestore, args: argparse.Namespace, hash_: str,
                 gid: bytes, deadline: float) -> dict[str, Any]:
    """One rmw_zenoh service call: get(ALL_COMPLETE, no consolidation) with request CDR and attachment."""
    name, seq = args.service_type, 1
    key = data_key(args.domain, args.call_service, name, hash_)
    request = encode(store, f"{name}_Request", from_plain(store, f"{name}_Request", {}))
    replies = session.get(key, payload=request, attachment=make_attachment(seq, time.time_ns(), gid),
                          target=zenoh.QueryTarget.ALL_COMPLETE, consolidation=zenoh.ConsolidationMode.NONE,
                          timeout=max(0.1, deadline - time.monotonic()))
    for reply in replies:
        if reply.ok is None:
            raise Failure(f"service replied with an error: {reply.err.payload.to_string()}", key=key)
        msg, same = roundtrip(store, f"{name}_Response", reply.ok.payload.to_bytes())
        att = reply.ok.attachment
        rseq, _, rgid = parse_attachment(att.to_bytes()) if att is not None else (None, 0, b"")
        return {**to_plain(msg), "key": key, "roundtrip_identical": same, "request_hex": request.hex(),
                "seq_echoed": rseq == seq, "gid_echoed": rgid == gid}
    raise Failure("no service reply before the timeout", key=key)


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
               ready: threading.Event) -> None:
    """Selftest stand-in for an rmw_zenoh node: /hand0/tactile/raw at 100 Hz, /hand0/tactile/tare."""
    topic, tname, srv, sname = SELFTEST_TOPIC, SELFTEST_TYPE, SELFTEST_SERVICE, "std_srvs/srv/Trigger"
    hash_of = (lambda n: HUMBLE_HASH) if humble else (lambda n: ros_hash(store, n))
    with zenoh.open(make_config("peer", [connect], ["tcp/127.0.0.1:0"])) as s:
        zid, gid, live = str(s.info.zid()), secrets.token_bytes(16), s.liveliness()

        def on_query(q: zenoh.Query) -> None:
            seq, _, client_gid = parse_attachment(q.attachment.to_bytes())
            store.deserialize_cdr(q.payload.to_bytes(), f"{sname}_Request")
            resp = from_plain(store, f"{sname}_Response", {"success": True, "message": "tared 3 sensors"})
            q.reply(q.key_expr, encode(store, f"{sname}_Response", resp),
                    attachment=make_attachment(seq, time.time_ns(), client_gid))
        entities = (s.declare_queryable(data_key(0, srv, sname, hash_of(sname)), on_query, complete=True),
                    live.declare_token(f"@ros2_lv/0/{zid}/0/0/NN/%/%/mimic"),
                    live.declare_token(entity_token(0, zid, 10, "MP", topic, tname, hash_of(tname), PUB_QOS, "mimic")),
                    live.declare_token(entity_token(0, zid, 11, "SS", srv, sname, hash_of(sname), SUB_QOS, "mimic")))
        pub, seq = s.declare_publisher(data_key(0, topic, tname, hash_of(tname))), 0
        ready.set()
        while not stop.wait(0.01):  # the publishing period, not a wait for discovery
            seq, now = seq + 1, time.time_ns()
            frame = {"header": {"stamp": {"sec": now // 10**9, "nanosec": now % 10**9}, "frame_id": "hand0"},
                     "pressure_pa": [101325.0 + seq, 0.1 * seq, -3.5]}
            pub.put(encode(store, tname, from_plain(store, tname, frame)), attachment=make_attachment(seq, now, gid))
        del entities


def cmd_selftest(args: argparse.Namespace) -> dict[str, Any]:
    """Hashes vs published values, CDR and attachment layout, then router + mimic node + subscribe."""
    store, ours = load_typestore(args.msgs)
    wrong = {n: ros_hash(store, n) for n, h in PUBLISHED.items() if ros_hash(store, n) != f"RIHS01_{h}"}
    gid = bytes(range(16))
    manual = b"".join(bytes([len(k)]) + k.encode() + v for k, v in (  # varint lengths < 128 are one byte
        ("sequence_number", (7).to_bytes(8, "little", signed=True)),
        ("source_timestamp", (-1).to_bytes(8, "little", signed=True)), ("source_gid", bytes([16]) + gid)))
    checks: dict[str, Any] = {
        "published_hashes_match": not wrong, "mismatched": wrong,
        "attachment_layout": make_attachment(7, -1, gid) == manual == make_attachment(*parse_attachment(manual)),
        "default_roundtrips": all(roundtrip(store, n, encode(store, n, from_plain(store, n, {})))[1]
                                  for n in [*ours, *HASHED[:-1], "std_srvs/srv/Trigger_Request"])}
    with socket.socket() as probe:  # a free loopback port for the router
        probe.bind(("127.0.0.1", 0))
        endpoint = f"tcp/127.0.0.1:{probe.getsockname()[1]}"
    router = subprocess.Popen([sys.executable, __file__, "router", "--listen", endpoint, "--seconds", "120"],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        if not select.select([router.stdout], [], [], 10)[0] or "ready" not in router.stdout.readline():
            raise Failure("router did not start", endpoint=endpoint)
        checks["router_udp_sockets"] = udp_sockets(router.pid)
        for humble in (False, True):
            stop, ready = threading.Event(), threading.Event()
            node = threading.Thread(target=mimic_node, args=(store, endpoint, humble, stop, ready))
            node.start()
            try:
                ready.wait(10)
                checks["humble" if humble else "hashed"] = cmd_subscribe(argparse.Namespace(
                    msgs=args.msgs, connect=endpoint, domain=0, mode="peer", count=20, timeout=15, humble=humble,
                    topic=SELFTEST_TOPIC, type=SELFTEST_TYPE, call_service=SELFTEST_SERVICE,
                    service_type="std_srvs/srv/Trigger"))
            finally:
                stop.set()
                node.join()
    finally:
        router.stdin.close()
        router.wait(10)
    if wrong or not checks["attachment_layout"] or not checks["default_roundtrips"] or checks["router_udp_sockets"] \
            or any(r["received"] != 20 or r["gaps"] or not all(r["service"][k] for k in ("success", "seq_echoed",
                   "gid_echoed", "roundtrip_identical")) for r in (checks["hashed"], checks["humble"])):
        raise Failure("selftest failed", **checks)
    return checks


def main() -> int:
    """Parse arguments, run one subcommand, print its result; exit 1 with {"error": ...} on failure."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    commands = {"hashes": cmd_hashes, "cdr": cmd_cdr, "encode": cmd_encode, "subscribe": cmd_subscribe,
                "router": cmd_router, "selftest": cmd_selftest}
    ps = {name: sub.add_parser(name, help=fn.__doc__.splitlines()[0]) for name, fn in commands.items()}
    for name in ("hashes", "cdr", "encode", "subscribe", "selftest"):
        ps[name].add_argument("--msgs", type=Path, default=DEFAULT_MSGS, help="handstack_msgs or its msg/ folder")
    for name, extra in (("cdr", "--hex"), ("encode", "--json")):
        ps[name].add_argument("--type", required=True)
        ps[name].add_argument(extra, required=True)
    p = ps["subscribe"]
    p.add_argument("--connect", required=True)
    p.add_argument("--domain", type=int, default=0)
    p.add_argument("--mode", choices=("peer", "client"), default="peer")
    p.add_argument("--topic", default=SELFTEST_TOPIC)
    p.add_argument("--type", default=SELFTEST_TYPE)
    p.add_argument("--count", type=int, default=10)
    p.add_argument("--timeout", type=float, default=10.0, help="seconds for the whole run")
    p.add_argument("--humble", action="store_true", help="keys and tokens carry TypeHashNotSupported")
    p.add_argument("--call-service", help="e.g. /hand0/tactile/tare")
    p.add_argument("--service-type", default="std_srvs/srv/Trigger")
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
