//! The `marsden` command (placeholder until the CLI issue lands).

fn main() {
    println!("marsden: the command-line interface is not built yet");
}
