//! proptest over arbitrary byte streams: the packet parser never panics, a valid packet
//! after any garbage is still found (resynchronisation), and the borrowing parse reads what the
//! owning one does.

use hand_control::protocol::{Parser, encode};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn never_panics_on_arbitrary_bytes(chunks in prop::collection::vec(prop::collection::vec(any::<u8>(), 0..64), 0..16)) {
        let mut p = Parser::default();
        for c in &chunks {
            p.push(c);
            while p.next_packet().is_some() {}
        }
        // Whatever is left is at most an unfinished frame.
        prop_assert!(p.pending() <= 7 + hand_control::protocol::MAX_LEN);
    }

    #[test]
    fn resynchronises_after_garbage(
        garbage in prop::collection::vec(prop_oneof![Just(0xFFu8), Just(0xFD), Just(0x00), any::<u8>()], 0..200),
        id in 0u8..=252,
        instruction in any::<u8>(),
        params in prop::collection::vec(prop_oneof![Just(0xFFu8), Just(0xFD), any::<u8>()], 0..40),
        split in any::<prop::sample::Index>(),
    ) {
        let mut wire = garbage.clone();
        let tail = wire.len();
        encode(&mut wire, id, instruction, &params);
        // Garbage that opens a frame with a long length would swallow the packet, as it
        // would on a real bus; the sender's retry (a second copy) is then found.
        let mut second = Vec::new();
        encode(&mut second, id, instruction, &params);
        for _ in 0..(hand_control::protocol::MAX_LEN / second.len().max(1) + 2) {
            wire.extend_from_slice(&second);
        }
        let cut = split.index(wire.len());
        let mut p = Parser::default();
        let mut found = false;
        for part in [&wire[..cut], &wire[cut..]] {
            p.push(part);
            while let Some(r) = p.next_packet() {
                if let Ok(pkt) = r {
                    if pkt.id == id && pkt.instruction == instruction && pkt.params == params {
                        found = true;
                    }
                }
            }
        }
        prop_assert!(found, "packet after {} garbage bytes not found", tail);
    }

    #[test]
    fn the_borrowing_parse_reads_what_the_owning_parse_does(
        chunks in prop::collection::vec(prop::collection::vec(prop_oneof![Just(0xFFu8), Just(0xFD), Just(0x00), Just(0x03), any::<u8>()], 0..64), 0..16),
        packets in prop::collection::vec((0u8..=252, any::<u8>(), prop::collection::vec(any::<u8>(), 0..12)), 0..6),
    ) {
        // Good packets between the garbage chunks, pushed a chunk at a time.
        let mut parts = Vec::new();
        for (k, c) in chunks.iter().enumerate() {
            let mut part = c.clone();
            if let Some((id, instruction, params)) = packets.get(k) {
                encode(&mut part, *id, *instruction, params);
            }
            parts.push(part);
        }
        let (mut owning, mut borrowing) = (Parser::default(), Parser::default());
        for part in &parts {
            owning.push(part);
            borrowing.push(part);
            loop {
                let want = owning.next_packet();
                let got = borrowing.next_packet_ref().map(|r| r.map(|p| p.to_packet()));
                prop_assert_eq!(&got, &want);
                prop_assert_eq!(borrowing.pending(), owning.pending());
                if want.is_none() {
                    break;
                }
            }
        }
    }
}
