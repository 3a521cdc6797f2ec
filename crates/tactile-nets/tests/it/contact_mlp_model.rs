//! The contact MLP's centroid head, quadratic base and ensembles: trained, saved, loaded and
//! checked, with bad options and corrupt files refused; and the centroid head's log-rise
//! inputs.

use tactile_nets::NetError;
use tactile_nets::contact_mlp::{
    BASE_TERMS, ContactExample, ContactMlp, Head, LOG_RISE_FLOOR_HPA, Options, TapReading,
    features, head_inputs,
};
use tactile_nets::train::TrainConfig;

/// Tensor-name prefix of ensemble member `i` in a weights file: the first keeps a single
/// network's names.
fn member_prefix(i: usize) -> String {
    if i == 0 {
        "net.".to_owned()
    } else {
        format!("member{i}.net.")
    }
}

fn tap(held_pa: [f32; 3], arrival_ms: [Option<f32>; 3], centroid: [f32; 2]) -> ContactExample {
    let reading = TapReading {
        baseline_pa: [101_000.0; 3],
        held_pa,
        arrival_ms,
    };
    ContactExample {
        centroid,
        ..ContactExample::new(reading, 0)
    }
}

fn config(epochs: usize) -> TrainConfig {
    TrainConfig {
        epochs,
        batch_size: 2,
        learning_rate: 1e-2,
        l2: 0.0,
        seed: 1,
        progress: false,
        label: String::new(),
    }
}

/// No dropout, a quadratic base, `members` networks.
fn based(members: usize) -> Options {
    Options {
        dropout: 0.0,
        quadratic_base: true,
        members,
    }
}

/// Two contacts a cell and a half apart on row 1.
fn two_taps() -> [ContactExample; 2] {
    [
        tap(
            [102_000.0, 101_050.0, 104_000.0],
            [Some(9.0), None, Some(3.0)],
            [1.2, 1.3],
        ),
        tap(
            [104_000.0, 101_050.0, 102_000.0],
            [Some(3.0), None, Some(9.0)],
            [1.1, 5.8],
        ),
    ]
}

#[test]
fn the_centroid_head_learns_points_and_keeps_its_dropout() -> Result<(), NetError> {
    // The regression places each of the two taps in its cell.
    let taps = two_taps();
    let (mlp, _) = ContactMlp::train_with_dropout(&taps, Head::Centroid, 0.0, &config(300))?;
    assert!(mlp.quadratic_base().is_none());
    for (t, cell) in taps.iter().zip([0u16, 5]) {
        let p = mlp.predict(&features(&t.reading))?;
        assert_eq!(p.region, cell, "{p:?}");
        assert_eq!(p.contact, 1 << cell);
        let miss = (p.centroid[0] - t.centroid[0]).hypot(p.centroid[1] - t.centroid[1]);
        assert!(miss < 0.1, "{p:?} vs {:?}", t.centroid);
    }
    let loaded = ContactMlp::from_file(&mlp.to_file()?)?;
    assert_eq!(loaded.head(), Head::Centroid);
    // The dropout rate it was trained with survives the file: the loaded model writes it back.
    let dropout = loaded
        .to_file()?
        .metadata_json()?
        .get("dropout")
        .and_then(|d| d.as_f64());
    assert_eq!(dropout, Some(0.0));
    let x = features(&taps[0].reading);
    assert_eq!(loaded.outputs(&x)?, mlp.outputs(&x)?);
    for bad in [-0.1, 1.0, f32::NAN] {
        let r = ContactMlp::train_with_dropout(&taps, Head::Centroid, bad, &config(1));
        assert!(matches!(r, Err(NetError::Training(_))), "{bad}");
    }
    Ok(())
}

#[test]
fn a_quadratic_base_is_trained_saved_and_checked() -> Result<(), NetError> {
    let taps = two_taps();
    // Two taps: the base alone already passes through both (minimum-norm fit), and the
    // network, trained on what it leaves, must not undo that.
    let (mlp, _) = ContactMlp::train_with(&taps, Head::Centroid, &based(1), &config(50))?;
    assert!(mlp.quadratic_base().is_some());
    for t in &taps {
        let p = mlp.predict(&features(&t.reading))?;
        let miss = (p.centroid[0] - t.centroid[0]).hypot(p.centroid[1] - t.centroid[1]);
        assert!(miss < 0.1, "{p:?} vs {:?}", t.centroid);
    }
    let file = mlp.to_file()?;
    let loaded = ContactMlp::from_file(&file)?;
    assert_eq!(loaded.quadratic_base(), mlp.quadratic_base());
    let x = features(&taps[1].reading);
    assert_eq!(loaded.outputs(&x)?, mlp.outputs(&x)?);
    // Only the centroid head takes a base, in training and in a file.
    let r = ContactMlp::train_with(&taps, Head::CellSet, &based(1), &config(1));
    assert!(matches!(r, Err(NetError::Training(_))));
    let (cells, _) = ContactMlp::train_with_dropout(&taps, Head::CellSet, 0.0, &config(1))?;
    let mut bad = cells.to_file()?;
    bad.insert("base.quadratic", &[2, BASE_TERMS], &[0.0; 2 * BASE_TERMS])?;
    assert!(matches!(
        ContactMlp::from_file(&bad),
        Err(NetError::SafeTensors(_))
    ));
    // A corrupt coefficient is refused at load, not met as a NaN location later.
    let mut bad = file;
    bad.insert(
        "base.quadratic",
        &[2, BASE_TERMS],
        &[f32::NAN; 2 * BASE_TERMS],
    )?;
    assert!(matches!(
        ContactMlp::from_file(&bad),
        Err(NetError::SafeTensors(_))
    ));
    Ok(())
}

#[test]
fn an_ensemble_averages_its_members_and_round_trips() -> Result<(), NetError> {
    let taps = two_taps();
    let (one, one_log) = ContactMlp::train_with(&taps, Head::Centroid, &based(1), &config(20))?;
    let (three, log) = ContactMlp::train_with(&taps, Head::Centroid, &based(3), &config(20))?;
    assert_eq!((one.members(), three.members()), (1, 3));
    // Member 0 is the single network, bit for bit; members 1 and 2 are trained with the
    // next seeds, and the ensemble outputs the mean of the three on the shared base.
    let file = three.to_file()?;
    let prefixes: Vec<String> = (0..3).map(member_prefix).collect();
    let x = features(&taps[0].reading);
    let mut mean = [0.0f32; 2];
    for (i, prefix) in prefixes.iter().enumerate() {
        let mut single = one.to_file()?;
        for name in file.names().filter(|n| n.starts_with(prefix.as_str())) {
            let t = file
                .tensor(name)
                .ok_or_else(|| NetError::MissingTensor(name.into()))?;
            single.insert(&format!("net.{}", &name[prefix.len()..]), &t.shape, &t.data)?;
        }
        let member = ContactMlp::from_file(&single)?;
        if i == 0 {
            assert_eq!(member.outputs(&x)?, one.outputs(&x)?);
        }
        let y = member.outputs(&x)?;
        mean = [mean[0] + y[0] / 3.0, mean[1] + y[1] / 3.0];
    }
    let y = three.outputs(&x)?;
    assert!(
        (y[0] - mean[0]).abs() < 1e-4 && (y[1] - mean[1]).abs() < 1e-4,
        "{y:?} {mean:?}"
    );
    assert_ne!(y, one.outputs(&x)?);
    // The log is the members' mean: not the first member's alone.
    assert_eq!(log.epoch_loss.len(), 20);
    assert_ne!(log.epoch_loss, one_log.epoch_loss);
    // Saved and loaded, it predicts the same; the single network's file names no members.
    let loaded = ContactMlp::from_file(&file)?;
    assert_eq!((loaded.members(), loaded.outputs(&x)?), (3, y));
    assert!(file.metadata_json()?.get("members").is_some());
    assert!(one.to_file()?.metadata_json()?.get("members").is_none());
    // Refused: no members, members of another head, a member count a file cannot back.
    for (head, members) in [
        (Head::Centroid, 0),
        (Head::CellSet, 2),
        (Head::Centroid, 65),
    ] {
        let options = Options {
            members,
            ..based(1)
        };
        let options = Options {
            quadratic_base: head == Head::Centroid,
            ..options
        };
        let r = ContactMlp::train_with(&taps, head, &options, &config(1));
        assert!(
            matches!(r, Err(NetError::Training(_))),
            "{head:?} {members}"
        );
    }
    for members in ["0", "65", "\"3\"", "-1"] {
        let mut bad = file.clone();
        let meta = file
            .metadata()
            .replace("\"members\":3", &format!("\"members\":{members}"));
        bad.set_metadata(meta);
        assert!(
            matches!(ContactMlp::from_file(&bad), Err(NetError::SafeTensors(_))),
            "{members}"
        );
    }
    // Four members named, three stored: the missing one is named.
    let mut bad = file.clone();
    bad.set_metadata(file.metadata().replace("\"members\":3", "\"members\":4"));
    assert!(ContactMlp::from_file(&bad).is_err());
    Ok(())
}

#[test]
fn the_centroid_head_reads_log_rises() {
    let raw = [10.0, 0.0, -3.0, 0.5, 0.0, 0.5, 0.0, 12.0, 3.0];
    let x = head_inputs(Head::Centroid, raw);
    assert!((x[0] - 10.0f32.ln()).abs() < 1e-6);
    assert_eq!(x[1], LOG_RISE_FLOOR_HPA.ln());
    assert_eq!(x[2], LOG_RISE_FLOOR_HPA.ln());
    assert_eq!(x[3..], raw[3..]);
    for head in Head::PAPER {
        assert_eq!(head_inputs(head, raw), raw);
    }
}
