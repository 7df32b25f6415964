//! Every variable of a component as bits, for bit-for-bit comparisons. Mount with
//! `#[path = "common/outputs.rs"] mod outputs;`.

use raceway::component::variables;
use raceway::Component;

/// Every variable of the table, read from `c`, as bits.
pub fn outputs(c: &mut Component) -> Vec<u64> {
    variables::all()
        .map(|v| c.get_real(v.vr).unwrap().to_bits())
        .collect()
}
