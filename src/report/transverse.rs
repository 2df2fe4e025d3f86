//! Scene T's summary: the Fig. 8-like table of mean FFx and a Fig. 5-like plot.

pub fn print_summary(_out_dir: &std::path::Path) -> std::io::Result<()> {
    Ok(())
}
