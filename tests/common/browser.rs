//! Loads a local, self-contained HTML file in a real headless Chromium (Debian's `chromium`) and
//! reports what a browser test checks: console errors, a screenshot and how much is drawn on it,
//! and the DOM after load.
//!
//! Chromium is driven over the DevTools protocol on a pipe (`--remote-debugging-pipe`: it reads
//! NUL-terminated JSON commands on fd 3 and writes replies and events on fd 4), not by parsing
//! `--enable-logging=stderr`. That log prints every console message of a web page at INFO
//! (`INFO:CONSOLE:4] "boom", source: file:///…/page.html (4)` for `console.log` and
//! `console.error` alike) and never prints failed resource loads, which the protocol reports
//! with their level (`Runtime.consoleAPICalled`, `Runtime.exceptionThrown`, `Log.entryAdded`).
//!
//! One run: a private profile in a temporary directory, every host name resolving to nothing
//! (`--host-resolver-rules`, so a page that fetches from the network shows a failed load rather
//! than reaching it), the viewport set to exactly `window` CSS pixels at scale 1, the page loaded,
//! then 5 s of virtual time (timers fast-forwarded, no real waiting) before the DOM and the
//! screenshot are taken. Chromium runs in its own process group and all of it is killed if the
//! whole run takes more than 60 s.

use std::collections::HashMap;
use std::io::{Read, Write};
use std::os::fd::AsRawFd;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

/// Longest a whole check may take (start, load, screenshot, exit) before Chromium is killed.
const TIMEOUT: Duration = Duration::from_secs(60);
/// Virtual time given to the page after its load event (timers, animations), in milliseconds.
const VIRTUAL_TIME_BUDGET_MS: u64 = 5000;

/// What a headless Chromium saw of a page.
#[derive(Debug)]
pub struct PageCheck {
    /// `console.error` calls, failed `console.assert`s, uncaught exceptions (and unhandled
    /// promise rejections) and error-level browser log entries such as failed resource loads,
    /// one line each as Chromium reports them with their source, e.g.
    /// `console.error: boom (file:///…/page.html:4)`,
    /// `Uncaught Error: x (file:///…/page.html:5)`,
    /// `network: Failed to load resource: net::ERR_FILE_NOT_FOUND (file:///…/missing.png)`.
    pub console_errors: Vec<String>,
    /// The screenshot of the viewport (kept until the `PageCheck` is dropped).
    pub screenshot_png: PathBuf,
    /// The screenshot's size in pixels: `window`, since the scale factor is 1.
    pub screenshot_size: (u32, u32),
    /// Distinct RGBA colours in the screenshot.
    pub distinct_colours: usize,
    /// Share of the screenshot's pixels that differ from its most common colour.
    pub non_background_fraction: f64,
    /// The document serialized after load and the virtual-time budget (doctype included).
    pub dom: String,
    _out: tempfile::TempDir,
}

/// Loads `html` (a local file) in headless Chromium with a `window` = (width, height) viewport.
///
/// Without `chromium` on `PATH` the test fails naming `apt-get install chromium`, unless the run
/// opted out of the external checks: then `None`, counted ([`super::external::unavailable`]). Panics with Chromium's stderr
/// when it cannot start, crashes, cannot open the file or does not finish within 60 s.
pub fn check_page(html: &Path, window: (u32, u32)) -> Option<PageCheck> {
    let Some(exe) = chromium() else {
        super::external::unavailable(
            &format!("the browser check of {}", html.display()),
            "chromium is not on PATH",
            "apt-get install chromium",
        );
        return None;
    };
    let html = html
        .canonicalize()
        .unwrap_or_else(|e| panic!("{}: {e}", html.display()));
    let profile = tempfile::tempdir().expect("tempdir for the chromium profile");
    let out = tempfile::tempdir().expect("tempdir for the screenshot");
    let mut cdp = Cdp::launch(&exe, profile.path(), window);

    let target = cdp.call("Target.createTarget", json!({"url": "about:blank"}), false);
    let target_id = target["targetId"].clone();
    let attached = cdp.call(
        "Target.attachToTarget",
        json!({"targetId": target_id, "flatten": true}),
        false,
    );
    cdp.session = attached["sessionId"].as_str().map(str::to_owned);
    assert!(cdp.session.is_some(), "no session: {attached}");
    for domain in ["Page", "Runtime", "Log"] {
        cdp.call(&format!("{domain}.enable"), json!({}), true);
    }
    cdp.call(
        "Emulation.setDeviceMetricsOverride",
        json!({"width": window.0, "height": window.1, "deviceScaleFactor": 1, "mobile": false}),
        true,
    );
    let url = file_url(&html);
    let nav = cdp.call("Page.navigate", json!({"url": url}), true);
    if let Some(e) = nav["errorText"].as_str() {
        cdp.fail(&format!("could not open {url}: {e}"));
    }
    while !cdp.loaded {
        cdp.next_event();
    }
    cdp.call(
        "Emulation.setVirtualTimePolicy",
        json!({"policy": "pauseIfNetworkFetchesPending", "budget": VIRTUAL_TIME_BUDGET_MS}),
        true,
    );
    while !cdp.budget_expired {
        cdp.next_event();
    }
    let doc = cdp.call("DOM.getDocument", json!({"depth": 0}), true);
    let dom = cdp.call(
        "DOM.getOuterHTML",
        json!({"nodeId": doc["root"]["nodeId"]}),
        true,
    )["outerHTML"]
        .as_str()
        .expect("outerHTML")
        .to_owned();
    let shot = cdp.call("Page.captureScreenshot", json!({"format": "png"}), true);
    let png = base64_decode(shot["data"].as_str().expect("screenshot data"));
    cdp.close();

    let screenshot_png = out.path().join("screenshot.png");
    std::fs::write(&screenshot_png, &png).expect("write the screenshot");
    let image = image::load_from_memory_with_format(&png, image::ImageFormat::Png)
        .expect("chromium's screenshot decodes as PNG")
        .to_rgba8();
    let mut counts: HashMap<[u8; 4], usize> = HashMap::new();
    for p in image.pixels() {
        *counts.entry(p.0).or_default() += 1;
    }
    let total = (image.width() as usize * image.height() as usize).max(1);
    let background = counts.values().copied().max().unwrap_or(0);
    Some(PageCheck {
        console_errors: std::mem::take(&mut cdp.errors),
        screenshot_png,
        screenshot_size: image.dimensions(),
        distinct_colours: counts.len(),
        non_background_fraction: (total - background) as f64 / total as f64,
        dom,
        _out: out,
    })
}

/// `chromium` (Debian) or `chromium-browser` on `PATH`.
fn chromium() -> Option<PathBuf> {
    use std::os::unix::fs::PermissionsExt;
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|dir| ["chromium", "chromium-browser"].map(|n| dir.join(n)))
        .find(|p| {
            p.metadata()
                .is_ok_and(|m| m.is_file() && m.permissions().mode() & 0o111 != 0)
        })
}

/// `file://` URL of an absolute path, bytes outside the unreserved set percent-encoded.
fn file_url(path: &Path) -> String {
    use std::os::unix::ffi::OsStrExt;
    let mut url = String::from("file://");
    for &b in path.as_os_str().as_bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            url.push(b as char);
        } else {
            url.push_str(&format!("%{b:02X}"));
        }
    }
    url
}

/// A running Chromium and its DevTools pipe.
struct Cdp {
    child: Child,
    to_chrome: Option<std::io::PipeWriter>,
    from_chrome: Receiver<Value>,
    next_id: u64,
    deadline: Instant,
    stderr_log: PathBuf,
    /// The page's session (flat mode), once attached.
    session: Option<String>,
    loaded: bool,
    budget_expired: bool,
    errors: Vec<String>,
}

impl Cdp {
    fn launch(exe: &Path, profile: &Path, window: (u32, u32)) -> Cdp {
        let (to_chrome_r, to_chrome_w) = std::io::pipe().expect("pipe");
        let (from_chrome_r, from_chrome_w) = std::io::pipe().expect("pipe");
        let (fd3, fd4) = (to_chrome_r.as_raw_fd(), from_chrome_w.as_raw_fd());
        let stderr_log = profile.join("chromium.stderr");
        let stderr = std::fs::File::create(&stderr_log).expect("chromium stderr file");
        let mut cmd = Command::new(exe);
        cmd.args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--remote-debugging-pipe",
            "--no-first-run",
            "--no-default-browser-check",
            "--disable-extensions",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--mute-audio",
            "--host-resolver-rules=MAP * ~NOTFOUND",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={},{}", window.0, window.1))
        .arg("about:blank")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(stderr)
        .process_group(0);
        // SAFETY: only async-signal-safe calls (fcntl, dup2, close) between fork and exec. The
        // pipe ends are first copied above fd 9 so that moving one onto 3 or 4 cannot clobber
        // the other; dup2 leaves the copies on 3 and 4 without close-on-exec.
        unsafe {
            cmd.pre_exec(move || {
                let high = [
                    libc::fcntl(fd3, libc::F_DUPFD, 10),
                    libc::fcntl(fd4, libc::F_DUPFD, 10),
                ];
                for (fd, target) in high.into_iter().zip([3, 4]) {
                    if fd < 0 || libc::dup2(fd, target) < 0 {
                        return Err(std::io::Error::last_os_error());
                    }
                    libc::close(fd);
                }
                Ok(())
            });
        }
        let child = cmd
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start {}: {e}", exe.display()));
        // Our copies of Chromium's ends: closed, so its exit ends the reader with EOF.
        drop((to_chrome_r, from_chrome_w));
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut reader = from_chrome_r;
            let mut buf = Vec::new();
            let mut chunk = [0u8; 65536];
            loop {
                let n = match reader.read(&mut chunk) {
                    Ok(0) | Err(_) => return,
                    Ok(n) => n,
                };
                buf.extend_from_slice(&chunk[..n]);
                while let Some(end) = buf.iter().position(|&b| b == 0) {
                    let msg: Vec<u8> = buf.drain(..=end).collect();
                    let value = serde_json::from_slice(&msg[..end]).unwrap_or_else(
                        |e| json!({"unparsed": format!("{e}: {}", String::from_utf8_lossy(&msg))}),
                    );
                    if tx.send(value).is_err() {
                        return;
                    }
                }
            }
        });
        Cdp {
            child,
            to_chrome: Some(to_chrome_w),
            from_chrome: rx,
            next_id: 0,
            deadline: Instant::now() + TIMEOUT,
            stderr_log,
            session: None,
            loaded: false,
            budget_expired: false,
            errors: Vec::new(),
        }
    }

    /// Sends `method`, on the page's session when `on_page`; returns its id.
    fn send(&mut self, method: &str, params: Value, on_page: bool) -> u64 {
        self.next_id += 1;
        let mut msg = json!({"id": self.next_id, "method": method, "params": params});
        if on_page {
            msg["sessionId"] = json!(self.session);
        }
        let mut bytes = serde_json::to_vec(&msg).expect("json");
        bytes.push(0);
        let written = match self.to_chrome.as_mut() {
            Some(w) => w.write_all(&bytes),
            None => Err(std::io::ErrorKind::BrokenPipe.into()),
        };
        if let Err(e) = written {
            self.fail(&format!("cannot send {method}: {e}"));
        }
        self.next_id
    }

    /// Sends `method` and returns its result, handling the events that arrive meanwhile.
    fn call(&mut self, method: &str, params: Value, on_page: bool) -> Value {
        let id = self.send(method, params, on_page);
        loop {
            let msg = self.next_message();
            if msg["id"].as_u64() == Some(id) {
                if msg.get("error").is_some() {
                    self.fail(&format!("{method} failed: {}", msg["error"]));
                }
                return msg["result"].clone();
            }
            self.handle(&msg);
        }
    }

    fn next_event(&mut self) {
        let msg = self.next_message();
        self.handle(&msg);
    }

    fn next_message(&mut self) -> Value {
        let left = self.deadline.saturating_duration_since(Instant::now());
        match self.from_chrome.recv_timeout(left) {
            Ok(v) => v,
            Err(RecvTimeoutError::Timeout) => {
                let stage = if self.loaded {
                    "after the load event"
                } else {
                    "before the load event"
                };
                self.fail(&format!("no result within {TIMEOUT:?}, {stage} (killed)"))
            }
            Err(RecvTimeoutError::Disconnected) => {
                let status = self.child.wait().ok();
                self.fail(&format!("chromium closed its pipe (exit: {status:?})"))
            }
        }
    }

    /// Notes an event: load progress, and console errors in `errors`.
    fn handle(&mut self, msg: &Value) {
        let p = &msg["params"];
        match msg["method"].as_str().unwrap_or("") {
            "Page.loadEventFired" => self.loaded = true,
            "Emulation.virtualTimeBudgetExpired" => self.budget_expired = true,
            "Runtime.consoleAPICalled" => {
                let kind = p["type"].as_str().unwrap_or("");
                if kind == "error" || kind == "assert" {
                    let args: Vec<String> = p["args"]
                        .as_array()
                        .into_iter()
                        .flatten()
                        .map(remote_object_text)
                        .collect();
                    let frame = &p["stackTrace"]["callFrames"][0];
                    self.errors.push(format!(
                        "console.{kind}: {}{}",
                        args.join(" "),
                        location(&frame["url"], &frame["lineNumber"])
                    ));
                }
            }
            "Runtime.exceptionThrown" => {
                let d = &p["exceptionDetails"];
                let what = d["exception"]["description"]
                    .as_str()
                    .and_then(|s| s.lines().next())
                    .map(str::to_owned)
                    .or_else(|| d["exception"].get("value").map(|v| v.to_string()))
                    .unwrap_or_default();
                let text = d["text"].as_str().unwrap_or("exception");
                self.errors.push(format!(
                    "{text} {what}{}",
                    location(&d["url"], &d["lineNumber"])
                ));
            }
            "Log.entryAdded" if p["entry"]["level"] == "error" => {
                let e = &p["entry"];
                self.errors.push(format!(
                    "{}: {}{}",
                    e["source"].as_str().unwrap_or("log"),
                    e["text"].as_str().unwrap_or(""),
                    location(&e["url"], &e["lineNumber"])
                ));
            }
            "Page.javascriptDialogOpening" => {
                // alert()/confirm() would block the page until answered: dismiss, and report it.
                self.errors.push(format!(
                    "javascript dialog ({}): {}",
                    p["type"].as_str().unwrap_or(""),
                    p["message"].as_str().unwrap_or("")
                ));
                self.send(
                    "Page.handleJavaScriptDialog",
                    json!({"accept": false}),
                    true,
                );
            }
            _ if msg.get("unparsed").is_some() => {
                self.fail(&format!("unreadable DevTools message: {}", msg["unparsed"]))
            }
            _ => {}
        }
    }

    /// Asks Chromium to quit and waits for it (killing it at the deadline).
    fn close(&mut self) {
        self.send("Browser.close", json!({}), false);
        self.to_chrome = None;
        while Instant::now() < self.deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        self.fail("did not exit after Browser.close (killed)");
    }

    fn kill(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            // The whole process group (the browser's zygote, renderer and GPU processes too).
            let pgid = self.child.id() as libc::pid_t;
            // SAFETY: plain kill(2) on the process group this Cdp created for Chromium.
            unsafe {
                libc::kill(-pgid, libc::SIGKILL);
            }
            let _ = self.child.wait();
        }
    }

    /// Kills Chromium and panics with `why` and the end of its stderr.
    fn fail(&mut self, why: &str) -> ! {
        self.kill();
        let log = std::fs::read_to_string(&self.stderr_log).unwrap_or_default();
        let lines: Vec<&str> = log
            .lines()
            .filter(|l| !l.contains(":ERROR:dbus/"))
            .collect();
        let tail = lines[lines.len().saturating_sub(30)..].join("\n");
        panic!("headless chromium: {why}\n--- chromium stderr (last lines) ---\n{tail}");
    }
}

impl Drop for Cdp {
    fn drop(&mut self) {
        self.kill();
    }
}

/// A console argument as text: strings bare, other values as JSON, objects by description.
fn remote_object_text(o: &Value) -> String {
    match (o.get("value"), o["description"].as_str()) {
        (Some(Value::String(s)), _) => s.clone(),
        (Some(v), _) => v.to_string(),
        (None, Some(d)) => d.to_owned(),
        (None, None) => o["type"].as_str().unwrap_or("?").to_owned(),
    }
}

/// ` (url:line)` with the 0-based protocol line made 1-based, ` (url)` without a line.
fn location(url: &Value, line: &Value) -> String {
    match (url.as_str().filter(|u| !u.is_empty()), line.as_u64()) {
        (Some(u), Some(l)) => format!(" ({u}:{})", l + 1),
        (Some(u), None) => format!(" ({u})"),
        (None, _) => String::new(),
    }
}

/// Standard base64 (the protocol's encoding of the screenshot).
fn base64_decode(text: &str) -> Vec<u8> {
    let value = |c: u8| -> u32 {
        match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => panic!("not base64: byte {c}"),
        }
    };
    let digits: Vec<u8> = text.bytes().filter(|&c| c != b'=').collect();
    let mut out = Vec::with_capacity(digits.len() * 3 / 4);
    for group in digits.chunks(4) {
        let n = group
            .iter()
            .enumerate()
            .fold(0u32, |n, (i, &c)| n | value(c) << (18 - 6 * i));
        out.extend_from_slice(&n.to_be_bytes()[1..group.len()]);
    }
    out
}
