//! Output files against hostile surroundings (issue items 2, 12 and 15):
//! every command writes through `shadelab_io::write_atomic`, so nothing is
//! written through a planted link, nothing but a regular file is replaced,
//! `-` is standard output, a full disk is an error and a closed pipe is not,
//! and a file name of any allowed length can be written.

mod support;

use std::os::unix::fs::FileTypeExt;
use std::process::{Command, Stdio};

use support::*;

const SMALL: &[&str] = &["--model", "cube", "--size", "16x16"];

fn render_args(output: &str) -> Vec<&str> {
    let mut args = vec!["render"];
    args.extend_from_slice(SMALL);
    args.extend_from_slice(&["-o", output]);
    args
}

#[test]
fn a_link_planted_under_the_old_temporary_name_is_not_followed() {
    // The shell plants `.out.png.PID.tmp` with its own process id, then
    // becomes shadelab (exec keeps the id): a predictable temporary name
    // would write the image through the link into the victim.
    let dir = tempfile::tempdir().unwrap();
    let victim = write(dir.path(), "victim.txt", "precious\n");
    let out = Command::new("sh")
        .arg("-c")
        .arg(r#"ln -s victim.txt ".out.png.$$.tmp" && exec "$0" "$@""#)
        .arg(bin())
        .args(render_args("out.png"))
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_ok(&out);
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious\n");
    assert!(is_png(&std::fs::read(dir.path().join("out.png")).unwrap()));
    // Nothing else was made or left behind.
    let names = entries(dir.path());
    assert_eq!(names.len(), 3, "{names:?}");
}

#[test]
fn what_is_not_a_regular_file_is_never_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("fifo.png");
    mkfifo(&fifo);
    for args in [
        render_args("fifo.png"),
        vec![
            "compare", "--model", "cube", "--size", "16x16", "-o", "fifo.png",
        ],
        vec!["quad", "--size", "9", "--angles", "0", "-o", "fifo.png"],
    ] {
        let out = run_within(
            command(dir.path(), &args),
            std::time::Duration::from_secs(60),
        );
        assert_fails(&out, 1, &["fifo.png", "a FIFO, not a regular file"]);
        let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
        assert!(kind.is_fifo(), "{args:?} replaced the FIFO");
    }
    // A device node, where this user may make one (root): `-o /dev/null`
    // run as root used to turn the device into a regular file.
    let device = dir.path().join("null");
    let made = Command::new("mknod")
        .arg(&device)
        .args(["c", "1", "3"])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if made {
        let out = run(dir.path(), &render_args("null"));
        assert_fails(&out, 1, &["a device, not a regular file"]);
        let kind = std::fs::symlink_metadata(&device).unwrap().file_type();
        assert!(kind.is_char_device());
    }
    // A directory, too, and no temporary file is left anywhere.
    std::fs::create_dir(dir.path().join("dir.png")).unwrap();
    assert_fails(
        &run(dir.path(), &render_args("dir.png")),
        1,
        &["a directory"],
    );
    let names = entries(dir.path());
    assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
}

#[test]
fn a_link_as_the_output_is_replaced_itself_not_written_through() {
    let dir = tempfile::tempdir().unwrap();
    let victim = write(dir.path(), "victim.txt", "precious\n");
    std::os::unix::fs::symlink(&victim, dir.path().join("out.png")).unwrap();
    assert_ok(&run(dir.path(), &render_args("out.png")));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious\n");
    let meta = std::fs::symlink_metadata(dir.path().join("out.png")).unwrap();
    assert!(meta.is_file(), "the link was followed");
}

#[test]
fn a_dash_writes_the_image_to_standard_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), &render_args("-"));
    assert_ok(&out);
    assert!(is_png(&out.stdout), "{} bytes on stdout", out.stdout.len());
    let image = png::Decoder::new(std::io::Cursor::new(&out.stdout))
        .read_info()
        .unwrap()
        .info()
        .clone();
    assert_eq!((image.width, image.height), (16, 16));
    assert!(entries(dir.path()).is_empty(), "{:?}", entries(dir.path()));
}

#[test]
fn a_full_disk_is_an_error_and_a_closed_pipe_is_not() {
    let dir = tempfile::tempdir().unwrap();
    let full = || std::fs::File::create("/dev/full").unwrap();
    // The image to a full standard output.
    let out = command(dir.path(), &render_args("-"))
        .stdout(full())
        .output()
        .unwrap();
    assert_fails(&out, 1, &["No space left on device"]);
    // A reader that stops after one byte: quiet, and success as `yes | head` is.
    let mut child = command(dir.path(), &render_args("-"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(!stderr(&out).contains("error"), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked"), "{}", stderr(&out));
}

#[test]
fn a_file_name_of_254_characters_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let name = format!("{}.png", "n".repeat(250));
    assert_eq!(name.len(), 254);
    assert_ok(&run(dir.path(), &render_args(&name)));
    assert!(is_png(&std::fs::read(dir.path().join(&name)).unwrap()));
    assert_eq!(entries(dir.path()), vec![name]);
}
