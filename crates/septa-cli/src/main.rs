//! The `septa` command line.
fn main() {
    println!("septa");
}
