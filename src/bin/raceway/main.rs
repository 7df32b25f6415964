//! The `raceway` command-line program.
fn main() {
    println!("raceway");
}
