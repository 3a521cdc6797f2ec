//! Nothing panics on any scene text: arbitrary strings, and the committed scene files with
//! bytes deleted, repeated or replaced. Every rejection carries a location inside the text.

use paper_scenes::scene::PaperScene as Scene;
use proptest::prelude::*;
use std::path::Path;

fn committed_scenes() -> Vec<String> {
    let dir = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/scenes"
    ));
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("fixtures/scenes")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| std::fs::read_to_string(p).expect("readable"))
        .collect();
    v.sort();
    v
}

fn check(text: &str) -> Result<(), TestCaseError> {
    if let Err(e) = Scene::parse("p.toml", text) {
        if let Some(at) = e.location() {
            let lines = text.split('\n').count();
            prop_assert!(at.line >= 1 && at.line <= lines, "{e} ({lines} lines)");
        }
        prop_assert!(!e.to_string().is_empty());
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        check(&text)?;
    }

    #[test]
    fn toml_shaped_text_never_panics(
        text in "(\\[[a-z_.]{1,20}\\]\n|[a-z_]{1,12} = (-?[0-9]{1,6}|\"[a-z/0-9]{0,8}\"|\\[[0-9, ]{0,10}\\]|true)\n){0,12}"
    ) {
        check(&text)?;
    }

    #[test]
    fn mutated_scene_files_never_panic(
        which in any::<prop::sample::Index>(),
        at in any::<prop::sample::Index>(),
        op in 0u8..3,
        byte in prop::sample::select(b"[]=\".,0x-9 \nazZ#{}".to_vec()),
        len in 1usize..12,
    ) {
        let scenes = committed_scenes();
        let mut text = scenes[which.index(scenes.len())].clone().into_bytes();
        let i = at.index(text.len());
        let j = (i + len).min(text.len());
        match op {
            0 => { text.drain(i..j); }
            1 => { let chunk: Vec<u8> = text[i..j].to_vec(); text.splice(i..i, chunk); }
            _ => text[i] = byte,
        }
        check(&String::from_utf8_lossy(&text))?;
    }
}
