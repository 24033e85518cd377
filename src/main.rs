fn main() {
    println!("romdyn {}", env!("CARGO_PKG_VERSION"));
}
