//! Gives the shared library `liboblique.so` the SONAME `liboblique.so.0`, so that programs linked
//! against it load any ABI-compatible `liboblique.so.0` (see `scripts/install-capi.sh`, which
//! installs `liboblique.so.0.<minor>.<patch>` with the links `liboblique.so.0` and
//! `liboblique.so`). Bump the number with `OBLIQUE_ABI_VERSION` in `src/lib.rs` on an
//! incompatible change of the C ABI.

/// The SONAME's major number.
const SONAME_MAJOR: u32 = 0;

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    let target = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    // ELF platforms with a GNU-compatible linker; macOS (install_name) and Windows have none.
    if target != "macos" && target != "ios" && target != "windows" {
        println!("cargo::rustc-cdylib-link-arg=-Wl,-soname,liboblique.so.{SONAME_MAJOR}");
    }
}
