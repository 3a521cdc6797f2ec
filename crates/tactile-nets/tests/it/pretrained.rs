//! The built-in models: the `'static` and the full models agree bit for bit, every committed
//! force-DNN and contact-MLP file reads and re-writes to its own bytes without dfdx, damaged
//! files are typed errors naming file and tensor, every model loads within the size budget, and the
//! README quotes the committed metrics.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tactile_nets::NetError;
use tactile_nets::contact_cnn::Variant;
use tactile_nets::contact_mlp::ContactMlp;
use tactile_nets::contact_mlp::{N_FEATURES, TapReading, features};
use tactile_nets::force_dnn::ForceDnn;
use tactile_nets::pretrained::{
    CONTACT_MLP_OSRS, FORCE_DNN_SIM, FORCE_DNN_TABLE1, ForceModel, SIZE_BUDGET_BYTES, SOFTNESS,
    SOFTNESS_SEED, built_in_bytes, contact_cnn, contact_mlp, contact_mlp_static, force_dnn,
    metrics, softness,
};

#[test]
fn static_and_full_models_agree_bit_for_bit() -> Result<(), NetError> {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for (model, fast) in [
        (ForceModel::Sim, &FORCE_DNN_SIM),
        (ForceModel::Table1, &FORCE_DNN_TABLE1),
    ] {
        let full = force_dnn(model)?;
        assert_eq!(full.range_gf(), fast.range_gf());
        for _ in 0..200 {
            let rise: [f32; 3] = core::array::from_fn(|_| rng.random_range(-0.5..3.0));
            let (a, b) = (full.estimate_gf(&rise)?, fast.estimate_gf(&rise)?);
            assert_eq!(a.to_bits(), b.to_bits(), "{model:?} {rise:?}: {a} vs {b}");
        }
    }
    for osr in CONTACT_MLP_OSRS {
        let full = contact_mlp(osr)?;
        let fast = contact_mlp_static(osr).ok_or(NetError::EmptyCatalogue)?;
        assert!(full.catalogue().iter().copied().eq(fast.catalogue()));
        for _ in 0..200 {
            let r = TapReading {
                baseline_pa: [101_000.0; 3],
                held_pa: core::array::from_fn(|_| rng.random_range(100_900.0..108_000.0)),
                arrival_ms: core::array::from_fn(|_| {
                    rng.random_bool(0.8).then(|| rng.random_range(0.0..60.0))
                }),
            };
            let x: [f32; N_FEATURES] = features(&r);
            assert_eq!(full.predict(&x)?, fast.predict(&x)?, "osr {osr}");
        }
    }
    assert!(contact_mlp_static(300).is_none());
    assert!(contact_mlp(300).is_err());
    Ok(())
}

/// Every committed weights file of `kind` (`force_dnn`, `contact_mlp`).
fn committed(kind: &str) -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models")
        .join(kind);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("the models directory")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "safetensors"))
        .collect();
    files.sort();
    files
}

/// The plain-array models write the tensors dfdx's module walk wrote (names, shapes, the
/// dropout rates): every committed file, trained through dfdx, comes back byte for byte, and
/// its estimates match dfdx's forward.
#[test]
fn committed_files_read_and_rewrite_to_their_own_bytes_without_dfdx() -> Result<(), NetError> {
    let (forces, mlps) = (committed("force_dnn"), committed("contact_mlp"));
    // Table 1's model, its 13 leave-one-out folds and the hand-sim model; 5 OSRs × 5 heads.
    assert_eq!((forces.len(), mlps.len()), (15, 25));
    for path in &forces {
        let bytes = std::fs::read(path)?;
        let dnn = ForceDnn::from_bytes(&path.display().to_string(), &bytes)?;
        assert!(dnn.to_file()?.to_bytes()? == bytes, "{}", path.display());
        let rise = [0.7, 1.9, 1.2];
        let (plain, reference) = (dnn.estimate_gf(&rise)?, dnn.estimate_gf_dfdx(&rise)?);
        assert!((plain - reference).abs() < 1e-3, "{plain} vs {reference}");
    }
    for path in &mlps {
        let bytes = std::fs::read(path)?;
        let mlp = ContactMlp::load(path)?;
        assert!(mlp.to_file()?.to_bytes()? == bytes, "{}", path.display());
    }
    Ok(())
}

#[test]
fn damaged_files_are_typed_errors_naming_file_and_tensor() -> Result<(), NetError> {
    let good = force_dnn(ForceModel::Table1)?.to_file()?;
    let dir = std::env::temp_dir().join(format!("tactile-nets-damaged-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let load = |name: &str, bytes: &[u8]| -> String {
        let path = dir.join(name);
        std::fs::write(&path, bytes)
            .map_err(NetError::from)
            .and_then(|()| ForceDnn::load(&path).map(|_| ()))
            .map_or_else(|e| e.to_string(), |()| "loaded".into())
    };
    let bytes = good.to_bytes()?;
    let truncated = load("truncated.safetensors", &bytes[..bytes.len() - 7]);
    assert!(
        truncated.starts_with(&format!("{}", dir.join("truncated.safetensors").display())),
        "{truncated}"
    );
    let mut shape = good.clone();
    shape.insert("input.mean", &[4], &[0.0; 4])?;
    let shape = load("shape.safetensors", &shape.to_bytes()?);
    assert!(
        shape.contains("shape.safetensors: tensor `input.mean`: stored [4]"),
        "{shape}"
    );
    let mut nan = good.clone();
    let w = nan.get("net.1.0.weight", &[16, 16])?.to_vec();
    let mut w2 = w.clone();
    w2[37] = f32::NAN;
    nan.insert("net.1.0.weight", &[16, 16], &w2)?;
    let nan = load("nan.safetensors", &nan.to_bytes()?);
    assert!(
        nan.contains("nan.safetensors: tensor `net.1.0.weight`: value 37 is not finite"),
        "{nan}"
    );
    let missing = ForceDnn::load(&dir.join("none.safetensors")).map(|_| ());
    let missing = missing.map_or_else(|e| e.to_string(), |()| "loaded".into());
    assert!(missing.contains("none.safetensors: io:"), "{missing}");
    assert_eq!(load("good.safetensors", &bytes), "loaded");
    std::fs::remove_dir_all(&dir)?;
    Ok(())
}

/// Every model's weights file loads from bytes without dfdx, and a damaged one is a typed error
/// naming it: truncated, a force DNN of a width none is built with.
#[test]
fn every_model_loads_from_bytes_and_names_them_in_its_errors() -> Result<(), NetError> {
    use tactile_nets::contact_cnn::ContactCnn;
    use tactile_nets::softness::SoftnessNet;
    let force = force_dnn(ForceModel::Table1)?.to_file()?.to_bytes()?;
    let mlp = contact_mlp(1024)?.to_file()?.to_bytes()?;
    let cnn = contact_cnn(Variant::Small)?.to_file()?.to_bytes()?;
    let soft = softness()?.to_file(serde_json::json!({}))?.to_bytes()?;
    assert_eq!(
        ForceDnn::from_bytes("f", &force)?,
        force_dnn(ForceModel::Table1)?
    );
    assert_eq!(ContactMlp::from_bytes("m", &mlp)?, contact_mlp(1024)?);
    assert_eq!(
        ContactCnn::from_bytes("c", &cnn)?,
        contact_cnn(Variant::Small)?
    );
    assert_eq!(SoftnessNet::from_bytes("s", &soft)?, softness()?);
    let cut = |b: &[u8]| b[..b.len() - 5].to_vec();
    let errors = [
        ForceDnn::from_bytes("tip-force.safetensors", &cut(&force)).map(|_| ()),
        ContactMlp::from_bytes("tip-mlp.safetensors", &cut(&mlp)).map(|_| ()),
        ContactCnn::from_bytes("pad-cnn.safetensors", &cut(&cnn)).map(|_| ()),
        SoftnessNet::from_bytes("hand-soft.safetensors", &cut(&soft)).map(|_| ()),
    ];
    for (e, name) in errors
        .into_iter()
        .zip(["tip-force", "tip-mlp", "pad-cnn", "hand-soft"])
    {
        let text = e.expect_err("truncated").to_string();
        assert!(text.starts_with(&format!("{name}.safetensors: ")), "{text}");
    }
    let mut odd = force_dnn(ForceModel::Table1)?.to_file()?;
    odd.insert("net.0.0.weight", &[5, 3], &[0.1; 15])?;
    let text = ForceDnn::from_bytes("odd.safetensors", &odd.to_bytes()?)
        .expect_err("width 5")
        .to_string();
    assert!(
        text.contains("odd.safetensors: tensor `net.0.0.weight`: stored [5, 3]"),
        "{text}"
    );
    Ok(())
}

/// Kim et al. 2020, Table 1: 100 gf raised the sensors by 0.71, 0.53 and 0.63 hPa; a press
/// 40 times as hard (4 kgf, past the 0–200 gf the models were trained on) saturates the
/// network, and the estimate says so instead of passing for a measurement.
#[test]
fn a_force_beyond_the_rated_range_is_flagged() -> Result<(), NetError> {
    use tactile_nets::ForceEstimator;
    use tactile_nets::force_dnn::valid_range_gf;
    for model in ForceModel::ALL {
        let mut fast = model.dnn();
        let mut full = force_dnn(model)?;
        let [lo, hi] = valid_range_gf(fast.range_gf());
        assert_eq!([lo, hi], [-5.0, 205.0], "{model:?}");
        let rated = [0.71f32, 0.53, 0.63];
        let f = fast.estimate_force(&rated)?;
        assert!(f.in_range, "{model:?}: {} gf", f.gram_force());
        let hard = rated.map(|r| 40.0 * r);
        let (f, g) = (fast.estimate_force(&hard)?, full.estimate_force(&hard)?);
        assert!(
            !f.in_range && f.gram_force() > hi,
            "{model:?}: {} gf",
            f.gram_force()
        );
        assert_eq!(
            f, g,
            "{model:?}: the full model flags as the static one does"
        );
    }
    Ok(())
}

#[test]
fn every_built_in_model_loads_within_the_budget() -> Result<(), NetError> {
    for v in Variant::ALL {
        assert_eq!(contact_cnn(v)?.variant(), v);
    }
    let net = softness()?;
    assert!(net.sample_outputs(&[1.0; 8]).is_ok());
    // The `'static` softness net is the file's, bit for bit, and the metrics file's selection.
    assert_eq!(SOFTNESS, net);
    let selected = metrics("softness")?
        .row("selected")
        .and_then(|r| r.values.get("lm_seed").copied());
    assert_eq!(selected, Some(SOFTNESS_SEED as f64));
    for kind in ["force_dnn", "contact_mlp", "contact_cnn", "softness"] {
        assert!(!metrics(kind)?.rows.is_empty(), "{kind}");
    }
    assert!(metrics("nothing").is_err());
    let bytes = built_in_bytes();
    assert!(bytes <= SIZE_BUDGET_BYTES, "{bytes} B");
    Ok(())
}

/// The README's table of built-in models quotes their metrics files: a retrained model
/// must not leave it stale.
#[test]
fn the_readme_quotes_the_built_in_metrics() -> Result<(), NetError> {
    let readme = include_str!("../../README.md");
    let value = |kind: &str, row: &str, key: &str| -> Result<f64, NetError> {
        metrics(kind)?
            .row(row)
            .and_then(|r| r.values.get(key).copied())
            .ok_or_else(|| NetError::Metrics(format!("{kind}: {row}/{key}")))
    };
    let pct = |v: f64| format!("{:.1}", 100.0 * v);
    let mlp: Vec<String> = CONTACT_MLP_OSRS
        .iter()
        .map(|o| value("contact_mlp", &format!("osr{o}/chosen"), "area_accuracy").map(pct))
        .collect::<Result<_, _>>()?;
    let cnn: Vec<String> = Variant::ALL
        .iter()
        .map(|v| {
            value(
                "contact_cnn",
                &format!("committed/{}", v.name()),
                "accuracy",
            )
            .map(pct)
        })
        .collect::<Result<_, _>>()?;
    let seed = SOFTNESS_SEED;
    let quoted = [
        format!(
            "fit RMSE {:.3} gf",
            value("force_dnn", "table1/fit", "rmse_gf")?
        ),
        format!(
            "leave-one-out RMSE {:.1} gf",
            value("force_dnn", "table1/loocv", "rmse_gf")?
        ),
        format!(
            "RMSE {:.2} gf per frame",
            value("force_dnn", "sim/frames", "rmse_gf")?
        ),
        format!(
            "{:.2} gf per held step",
            value("force_dnn", "sim/steps", "rmse_gf")?
        ),
        format!("area accuracy {} %", mlp.join(" / ")).replace("100.0", "100"),
        format!("{} % on the held-out taps", cnn.join(" / ")),
        format!(
            "regular objects {} %, irregular {} %",
            pct(value(
                "softness",
                &format!("lm/seed{seed}"),
                "regular_accuracy"
            )?),
            pct(value(
                "softness",
                &format!("lm/seed{seed}"),
                "irregular_accuracy"
            )?)
        )
        .replace("100.0", "100"),
        format!("take {} KiB", (built_in_bytes() as f64 / 1024.0).round()),
    ];
    for q in quoted {
        assert!(readme.contains(&q), "README does not say `{q}`");
    }
    Ok(())
}
