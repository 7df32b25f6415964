//! Link flags of the FMU binary.
//!
//! `-z nodelete`: fmpy (and other hosts) `dlclose` the library in `freeInstance`; Rust's
//! thread-local destructors registered by a dlclose'd library crash the host at thread exit
//! (rust-lang/rust#59629, #88737, #91979). With `nodelete` the library stays mapped.
fn main() {
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") {
        println!("cargo::rustc-cdylib-link-arg=-Wl,-z,nodelete");
    }
    println!("cargo::rerun-if-changed=build.rs");
}
