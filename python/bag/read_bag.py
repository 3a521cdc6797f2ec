"""Reads a rosbag2 bag (MCAP storage) with two readers no one here wrote, and prints what each
saw as one JSON object on stdout, for handstack's recording tests to check.

    python read_bag.py BAG_DIR

- `rosbags`: the bag's metadata.yaml and its .mcap; each topic's type built from the message
  definition the bag carries (not from a type store), its RIHS01 hash computed from that and
  compared with the hash the bag declares, every message decoded from CDR;
- `mcap` + `mcap-ros2-support` (Foxglove's Python reader and ROS 2 decoder), the .mcap alone.

Decoded values are reported per topic: counts, and the fields the tests compare.
"""

import json
import math
import sys
from pathlib import Path


def plain(msg, typename):
    """The fields the tests compare, from a decoded message of either reader."""
    short = typename.split('/')[-1]
    if short == 'GraspState':
        return {'pressure_pa': msg.pressure_pa, 'effort': msg.effort, 'mode': msg.mode,
                'in_contact': bool(msg.in_contact), 'frame_id': msg.header.frame_id}
    if short == 'PressureFrame':
        return {'pressure_pa': [float(p) for p in msg.pressure_pa]}
    if short == 'GripperCommand':
        return {'effort': msg.effort, 'position_rad': msg.position_rad}
    if short == 'JointState':
        return {'name': list(msg.name), 'position': [float(p) for p in msg.position]}
    if short == 'Figure':
        return {'name': msg.name, 'value': msg.value, 'unit': msg.unit, 'met': msg.met,
                'target': msg.target}
    if short == 'Fault':
        return {'source': msg.source, 'what': msg.what, 'ends_run': bool(msg.ends_run)}
    if short == 'FingerFrame':
        return {'force_n': [float(f) for f in msg.force_n],
                'distal_angle_rad': [float(a) for a in msg.distal_angle_rad]}
    if short == 'TactileState':
        return {'sensors': [{'name': c.name, 'values': [float(v) for v in c.values]}
                            for c in msg.sensors]}
    if short == 'Label':
        return {'experiment': msg.experiment, 'name': msg.name, 'value': msg.value,
                'start_ns': msg.start.sec * 10**9 + msg.start.nanosec,
                'end_ns': msg.end.sec * 10**9 + msg.end.nanosec,
                'frame_id': msg.header.frame_id}
    if short == 'Softness':
        return {'level': msg.level, 'label': msg.label, 'scores': [float(s) for s in msg.scores]}
    return {}


def nan_free(v):
    """JSON has no NaN: NaN becomes None."""
    if isinstance(v, float) and math.isnan(v):
        return None
    if isinstance(v, dict):
        return {k: nan_free(x) for k, x in v.items()}
    if isinstance(v, list):
        return [nan_free(x) for x in v]
    return v


def with_rosbags(bag):
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import Stores, get_typestore, get_types_from_msg

    store = get_typestore(Stores.EMPTY)
    out = {'topics': {}}
    with Reader(bag) as reader:
        out['message_count'] = reader.message_count
        out['duration_ns'] = reader.duration
        out['start_ns'] = reader.start_time
        out['end_ns'] = reader.end_time
        out['ros_distro'] = reader.ros_distro
        for c in reader.connections:
            store.register(get_types_from_msg(c.msgdef.data, c.msgtype))
        for c in reader.connections:
            out['topics'][c.topic] = {
                'type': c.msgtype,
                'declared_count': c.msgcount,
                'declared_hash': c.digest,
                'hash_from_definition': store.hash_rihs01(c.msgtype),
                'qos': [q.__dict__ if hasattr(q, '__dict__') else str(q)
                        for q in c.ext.offered_qos_profiles],
                'count': 0,
                'messages': [],
            }
        for c, t, raw in reader.messages():
            msg = store.deserialize_cdr(raw, c.msgtype)
            topic = out['topics'][c.topic]
            topic['count'] += 1
            topic['messages'].append(plain(msg, c.msgtype))
    for topic in out['topics'].values():
        topic['qos'] = len(topic['qos'])
    return out


def with_mcap(bag):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    files = sorted(Path(bag).glob('*.mcap'))
    out = {'topics': {}, 'profile': None}
    with open(files[0], 'rb') as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        out['profile'] = reader.get_header().profile
        for schema, channel, _message, decoded in reader.iter_decoded_messages(log_time_order=False):
            topic = out['topics'].setdefault(channel.topic, {
                'type': schema.name, 'schema_encoding': schema.encoding,
                'message_encoding': channel.message_encoding,
                'metadata_keys': sorted(channel.metadata), 'count': 0, 'messages': []})
            topic['count'] += 1
            topic['messages'].append(plain(decoded, schema.name))
    return out


def main():
    bag = Path(sys.argv[1])
    result = {'rosbags': with_rosbags(bag)}
    try:
        import mcap  # noqa: F401
        import mcap_ros2  # noqa: F401
    except ImportError as e:
        result['mcap'] = {'missing': str(e)}
    else:
        result['mcap'] = with_mcap(bag)
    json.dump(nan_free(result), sys.stdout)


if __name__ == '__main__':
    main()
