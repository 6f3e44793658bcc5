//! Refuses requests whose `Host` or `Origin` header is not the server's own, so
//! that a web page elsewhere cannot reach the editor through DNS rebinding or a
//! cross-site request.

use std::net::SocketAddr;

use axum::http::{header, HeaderMap};

/// The `host:port` names the server answers to.
#[derive(Debug, Clone)]
pub struct HostGuard {
    allowed: Vec<String>,
}

impl HostGuard {
    /// The names for a server bound to `bound`: 127.0.0.1, localhost and
    /// [::1] on its port, its own address unless it is unspecified, and `extra`
    /// host names (with the port added when they have none).
    pub fn new(bound: SocketAddr, extra: &[String]) -> Self {
        let port = bound.port();
        let mut allowed = vec![
            format!("127.0.0.1:{port}"),
            format!("localhost:{port}"),
            format!("[::1]:{port}"),
        ];
        if !bound.ip().is_unspecified() {
            allowed.push(bound.to_string());
        }
        for name in extra {
            let name = name.to_ascii_lowercase();
            if name
                .rsplit_once(':')
                .is_some_and(|(_, p)| p.parse::<u16>().is_ok())
            {
                allowed.push(name);
            } else {
                allowed.push(format!("{name}:{port}"));
            }
        }
        HostGuard { allowed }
    }

    fn allows(&self, host_port: &str) -> bool {
        let host_port = host_port.to_ascii_lowercase();
        self.allowed.contains(&host_port)
    }

    /// `Ok` when the `Host` header names this server and the `Origin` header,
    /// if any, is `http://` and one of its names.
    ///
    /// # Errors
    ///
    /// A message naming the header at fault.
    pub fn check(&self, headers: &HeaderMap) -> Result<(), String> {
        let host = headers
            .get(header::HOST)
            .and_then(|v| v.to_str().ok())
            .unwrap_or("");
        if !self.allows(host) {
            return Err(format!("Host {host:?} is not this server"));
        }
        if let Some(origin) = headers.get(header::ORIGIN) {
            let origin = origin.to_str().unwrap_or("");
            let ok = origin
                .strip_prefix("http://")
                .is_some_and(|rest| self.allows(rest));
            if !ok {
                return Err(format!("Origin {origin:?} is not this server"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use axum::http::HeaderValue;

    fn headers(host: &str, origin: Option<&str>) -> HeaderMap {
        let mut h = HeaderMap::new();
        h.insert(header::HOST, HeaderValue::from_str(host).unwrap());
        if let Some(o) = origin {
            h.insert(header::ORIGIN, HeaderValue::from_str(o).unwrap());
        }
        h
    }

    #[test]
    fn own_names_pass_and_others_are_refused() {
        let g = HostGuard::new("127.0.0.1:8000".parse().unwrap(), &["editor.lan".into()]);
        assert!(g.check(&headers("127.0.0.1:8000", None)).is_ok());
        assert!(g
            .check(&headers("LOCALHOST:8000", Some("http://localhost:8000")))
            .is_ok());
        assert!(g.check(&headers("editor.lan:8000", None)).is_ok());
        assert!(g.check(&headers("evil.example:8000", None)).is_err());
        assert!(g.check(&headers("127.0.0.1:8001", None)).is_err());
        assert!(g
            .check(&headers("127.0.0.1:8000", Some("http://evil.example")))
            .is_err());
        assert!(g.check(&headers("127.0.0.1:8000", Some("null"))).is_err());
    }
}
