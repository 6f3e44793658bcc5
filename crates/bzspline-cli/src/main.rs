//! The `bzspline` command.

fn main() {
    println!("bzspline: command-line interface under construction");
}
