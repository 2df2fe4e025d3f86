//! Scene O report (being written).

pub fn print_summary(_out_dir: &std::path::Path) -> std::io::Result<()> {
    Ok(())
}
