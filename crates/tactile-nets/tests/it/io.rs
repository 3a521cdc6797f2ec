//! Safetensors files: bytes round trip and are deterministic, a dfdx module round trips bit
//! for bit, and wrong shapes and missing tensors are typed errors.

use dfdx::prelude::*;
use tactile_nets::NetError;
use tactile_nets::io::TensorFile;

#[test]
fn bytes_round_trip_and_are_deterministic() -> Result<(), NetError> {
    let mut f = TensorFile::new();
    f.insert("b", &[2], &[1.5, -0.0])?;
    f.insert("a", &[2, 1], &[f32::MIN_POSITIVE, 3.0])?;
    f.set_metadata("{\"model\":\"x\"}".to_owned());
    let bytes = f.to_bytes()?;
    assert_eq!(bytes, f.clone().to_bytes()?);
    let back = TensorFile::from_bytes(&bytes)?;
    assert_eq!(back, f);
    assert!(matches!(
        f.get("a", &[2]),
        Err(NetError::TensorMismatch { .. })
    ));
    assert!(matches!(f.get("c", &[2]), Err(NetError::MissingTensor(_))));
    assert!(f.insert("d", &[3], &[1.0]).is_err());
    Ok(())
}

#[test]
fn module_round_trip_is_bit_identical() -> Result<(), NetError> {
    let dev = Cpu::seed_from_u64(7);
    let a = dev.build_module::<(Linear<3, 4>, ReLU, Linear<4, 2>), f32>();
    let mut b = Cpu::seed_from_u64(8).build_module::<(Linear<3, 4>, ReLU, Linear<4, 2>), f32>();
    let mut f = TensorFile::new();
    f.add_module("net.", &a)?;
    assert_eq!(f.names().count(), 4);
    TensorFile::from_bytes(&f.to_bytes()?)?.load_module("net.", &mut b)?;
    let x = dev.tensor([0.3f32, -1.0, 2.5]);
    let (ya, yb) = (a.forward(x.clone()).as_vec(), b.forward(x).as_vec());
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&ya), bits(&yb));
    Ok(())
}
