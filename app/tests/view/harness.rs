//! What the view tests share: a `twinray view` server in a child process, plain HTTP requests
//! to it, and Debian's chromium driven through chromedriver (WebDriver) by fantoccini.

use fantoccini::{Client, ClientBuilder, Locator};
use serde_json::Value;
use std::io::{BufRead, BufReader, Read, Write};
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A `twinray view` child, killed when dropped.
pub struct Server {
    child: Child,
    pub url: String,
    pub port: u16,
}

impl Drop for Server {
    /// Ctrl-C, as a user stops it: the server removes its built sets and exits.
    fn drop(&mut self) {
        // SAFETY: kill(2) on our own child's pid, which `wait` has not reaped yet.
        unsafe { libc::kill(self.child.id() as libc::pid_t, libc::SIGINT) };
        let ended = twinray_tests::cli::wait_within(&mut self.child, Duration::from_secs(10));
        let work = std::env::temp_dir().join(format!("twinray-view-{}", self.child.id()));
        // A second panic while a failed test unwinds would abort the test binary.
        if !std::thread::panicking() {
            assert!(ended.is_ok(), "twinray view did not end on Ctrl-C");
            assert!(!work.exists(), "twinray view left {} behind", work.display());
        }
    }
}

impl Server {
    /// Starts `twinray view ARGS --port 0` in `dir` and waits for the address it prints.
    pub fn start(args: &[&str], dir: &Path) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_twinray"))
            .arg("view")
            .args(args)
            .args(["--port", "0"])
            .current_dir(dir)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("starting twinray view");
        let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
        let first = lines.next().and_then(Result::ok).unwrap_or_default();
        // Keep the rest of its output flowing (to the test's output) so it never blocks.
        std::thread::spawn(move || lines.map_while(Result::ok).for_each(|l| println!("[view] {l}")));
        let url = first
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap_or_else(|| panic!("twinray view printed no address: {first:?}"));
        let port = url.trim_end_matches('/').rsplit(':').next().unwrap().parse().unwrap();
        Server { child, url: url.to_string(), port }
    }

    /// (status code, body) of a raw HTTP/1.1 request, with `host` as its Host header.
    pub fn request(&self, method: &str, path: &str, host: &str, body: &str) -> (u16, String) {
        let mut stream = std::net::TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        stream.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
        let head = format!(
            "{method} {path} HTTP/1.1\r\nHost: {host}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
            body.len()
        );
        stream.write_all(head.as_bytes()).unwrap();
        let mut text = String::new();
        stream.read_to_string(&mut text).unwrap();
        let status = text.split_whitespace().nth(1).and_then(|c| c.parse().ok()).unwrap_or(0);
        let body = text.split_once("\r\n\r\n").map_or("", |(_, b)| b).to_string();
        (status, body)
    }

    pub fn get(&self, path: &str) -> (u16, String) {
        self.request("GET", path, &format!("127.0.0.1:{}", self.port), "")
    }

    /// The page's state, as the server holds it.
    pub fn state(&self) -> Value {
        let (status, body) = self.get("/state");
        assert_eq!(status, 200, "{body}");
        serde_json::from_str(&body).unwrap()
    }

    /// Waits up to `limit` for the state to satisfy `ready`; the last state seen.
    pub fn wait_for(&self, limit: Duration, what: &str, ready: impl Fn(&Value) -> bool) -> Value {
        let start = Instant::now();
        loop {
            let state = self.state();
            if ready(&state) {
                return state;
            }
            assert!(start.elapsed() < limit, "{what}: not after {limit:?}; state {state:#}");
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

/// chromedriver in a child process, and a headless chromium session through it.
pub struct Browser {
    pub client: Client,
    driver: Child,
}

impl Browser {
    pub async fn start(profile: &Path) -> Browser {
        let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
        // Its own process group, so that a failing test ends the browser it started too.
        let driver = Command::new("chromedriver")
            .process_group(0)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver (cargo xtask setup installs Debian's chromium-driver)");
        // As root in a container chromium needs --no-sandbox; the rest keep it off the network
        // this machine does not have, and its window a fixed size for the screenshot.
        let args = [
            "--headless=new",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--window-size=1500,900",
            &format!("--user-data-dir={}", profile.display()),
        ];
        let capabilities = serde_json::json!({"goog:chromeOptions": {"binary": "/usr/bin/chromium", "args": args}});
        let capabilities = capabilities.as_object().unwrap().clone();
        let connector = hyper_util::client::legacy::connect::HttpConnector::new();
        let start = Instant::now();
        let client = loop {
            match ClientBuilder::new(connector.clone())
                .capabilities(capabilities.clone())
                .connect(&format!("http://127.0.0.1:{port}"))
                .await
            {
                Ok(client) => break client,
                Err(e) if start.elapsed() > Duration::from_secs(30) => panic!("no WebDriver session: {e}"),
                Err(_) => tokio::time::sleep(Duration::from_millis(200)).await,
            }
        };
        Browser { client, driver }
    }

    pub async fn js(&self, script: &str) -> Value {
        self.client.execute(script, vec![]).await.unwrap_or_else(|e| panic!("{script}: {e}"))
    }

    pub async fn text(&self, id: &str) -> String {
        self.client.find(Locator::Id(id)).await.unwrap().text().await.unwrap()
    }

    /// Waits up to `limit` until `script` returns true.
    pub async fn wait_for(&self, limit: Duration, script: &str) {
        let start = Instant::now();
        while self.js(script).await != Value::Bool(true) {
            assert!(start.elapsed() < limit, "not after {limit:?}: {script}");
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
    }

    pub async fn close(mut self) {
        let _ = self.client.clone().close().await;
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        // chromedriver and the chromium it started: left behind, chromium kept a core busy.
        if let Ok(group) = i32::try_from(self.driver.id()) {
            // SAFETY: kill(2) on the process group this browser's chromedriver leads.
            unsafe { libc::kill(-group, libc::SIGKILL) };
        }
        let _ = self.driver.wait();
    }
}
