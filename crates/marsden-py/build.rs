//! Empty: present only so that the `[build-dependencies]` of Cargo.toml are resolved (they
//! unify the host proc-macros' features with `cargo test --workspace`, see the comment there).

fn main() {}
