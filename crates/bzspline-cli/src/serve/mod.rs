//! `bzspline serve`: a local web server with an interactive editor for the
//! spline. The page moves control points and alphas; every fit is computed here
//! with the library and sent back as JSON with an SVG path of exact cubic
//! segments.

use bzspline_io::api;
mod guard;

use std::io::Write;
use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::Context;
use axum::body::{to_bytes, Body};
use axum::extract::{Request, State};
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::serve::ListenerExt;
use axum::{Json, Router};
use tokio::sync::Semaphore;

use api::{ApiError, ParseLimits};

const EDITOR_HTML: &str = include_str!("../../assets/editor.html");
const EDITOR_JS: &str = include_str!("../../assets/editor.js");
const EDITOR_CSS: &str = include_str!("../../assets/editor.css");

/// Options of `bzspline serve`.
#[derive(Debug, Clone, clap::Args)]
pub struct ServeArgs {
    /// Address to listen on. The default accepts connections from this machine
    /// only; give another address (e.g. 0.0.0.0) to expose the editor on purpose.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: IpAddr,
    /// Port to listen on; 0 picks a free one. The address is printed.
    #[arg(long, default_value_t = 8737)]
    pub port: u16,
    /// Another host name the server answers to (repeatable). Requests whose Host
    /// or Origin header names anything else than 127.0.0.1, localhost, [::1],
    /// --host or these are refused with 403 (protection from DNS rebinding).
    #[arg(long = "allow-host", value_name = "NAME")]
    pub allow_hosts: Vec<String>,
    /// Largest request body in bytes; larger ones get 413.
    #[arg(long, default_value_t = 1 << 20, value_name = "BYTES")]
    pub max_body: usize,
    /// Most control points in one request; more get 422.
    #[arg(long, default_value_t = 20_000, value_name = "N")]
    pub max_points: usize,
    /// Most curvature-comb samples in one request (samples per segment times
    /// points); more get 422.
    #[arg(long, default_value_t = 200_000, value_name = "N")]
    pub max_samples: usize,
    /// Time limit for one request (reading the body and fitting) in
    /// milliseconds; slower ones get 504.
    #[arg(long, default_value_t = 5_000, value_name = "MS", value_parser = clap::value_parser!(u64).range(1..))]
    pub timeout_ms: u64,
    /// Most fits computed at once; further ones get 503 at once. Bodies are
    /// received outside this cap (up to 16 per slot, further ones get 503), so
    /// slow uploads do not hold the fit slots.
    #[arg(long, default_value_t = 4, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub max_in_flight: u32,
    /// Do not log each fit to standard error.
    #[arg(long)]
    pub quiet: bool,
}

/// Bodies being received at once, per fit slot: slow uploads wait here, not
/// in the fit slots, and their memory stays bounded (each at most --max-body).
const UPLOADS_PER_FIT: usize = 16;

/// What every handler shares.
struct AppState {
    limits: ParseLimits,
    max_body: usize,
    timeout: Duration,
    in_flight: Arc<Semaphore>,
    uploads: Arc<Semaphore>,
    quiet: bool,
}

/// Runs the server until the process is stopped.
///
/// # Errors
///
/// When the address cannot be bound or the runtime cannot start.
pub fn run(args: &ServeArgs) -> anyhow::Result<()> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_io()
        .enable_time()
        .build()
        .context("starting the async runtime")?;
    runtime.block_on(serve(args))
}

async fn serve(args: &ServeArgs) -> anyhow::Result<()> {
    let addr = SocketAddr::new(args.host, args.port);
    let listener = tokio::net::TcpListener::bind(addr)
        .await
        .with_context(|| format!("binding {addr}"))?;
    let bound = listener.local_addr().context("reading the bound address")?;
    let guard = guard::HostGuard::new(bound, &args.allow_hosts);
    let state = Arc::new(AppState {
        limits: ParseLimits {
            max_points: args.max_points,
            max_samples: args.max_samples,
        },
        max_body: args.max_body,
        timeout: Duration::from_millis(args.timeout_ms),
        in_flight: Arc::new(Semaphore::new(
            usize::try_from(args.max_in_flight).unwrap_or(usize::MAX),
        )),
        uploads: Arc::new(Semaphore::new(
            usize::try_from(args.max_in_flight)
                .unwrap_or(usize::MAX)
                .saturating_mul(UPLOADS_PER_FIT),
        )),
        quiet: args.quiet,
    });
    let app = router(state, guard);
    let shown = if bound.ip().is_unspecified() {
        SocketAddr::new(IpAddr::from([127, 0, 0, 1]), bound.port())
    } else {
        bound
    };
    {
        let mut out = std::io::stdout().lock();
        writeln!(out, "bzspline editor: http://{shown}/").context("writing to stdout")?;
        out.flush().context("writing to stdout")?;
    }
    // Small JSON answers go out at once instead of waiting for the client's
    // delayed acknowledgement (Nagle's algorithm).
    let listener = listener.tap_io(|tcp| {
        let _ = tcp.set_nodelay(true);
    });
    axum::serve(listener, app).await.context("serving")
}

fn router(state: Arc<AppState>, guard: guard::HostGuard) -> Router {
    Router::new()
        .route(
            "/",
            get(|| async { asset(editor_page(), "text/html; charset=utf-8") }),
        )
        .route(
            "/editor.js",
            get(|| async { asset(EDITOR_JS, "text/javascript; charset=utf-8") }),
        )
        .route(
            "/editor.css",
            get(|| async { asset(EDITOR_CSS, "text/css; charset=utf-8") }),
        )
        .route("/api/fit", post(fit_handler))
        .fallback(|| async { error_response(&ApiError::new(404, "no such page")) })
        .layer(axum::middleware::from_fn(
            move |req: Request, next: axum::middleware::Next| {
                let verdict = guard.check(req.headers());
                async move {
                    match verdict {
                        Ok(()) => next.run(req).await,
                        Err(message) => error_response(&ApiError::new(403, message)),
                    }
                }
            },
        ))
        .with_state(state)
}

/// The editor's page with the paper's Example 1 (the command's own copy of
/// it) and the library's range of alpha in its data blocks.
fn editor_page() -> &'static str {
    static PAGE: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    PAGE.get_or_init(|| {
        let example = crate::input::example(1);
        let points: Vec<&[f64]> = example.coords.chunks(example.width).collect();
        let json = serde_json::to_string(&points).unwrap_or_else(|_| "[]".to_owned());
        // The library's range of alpha: the page clamps to it, never to its own.
        let range = format!(
            "[{},{}]",
            bzspline::text::Shortest(bzspline::ALPHA_MIN),
            bzspline::text::Shortest(bzspline::ALPHA_MAX)
        );
        EDITOR_HTML
            .replace("EXAMPLE_1_POINTS", &json)
            .replace("ALPHA_RANGE", &range)
    })
}

fn asset(body: &'static str, mime: &'static str) -> Response {
    let mut r = body.into_response();
    let h = r.headers_mut();
    h.insert(header::CONTENT_TYPE, HeaderValue::from_static(mime));
    h.insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static("default-src 'self'; img-src 'self' data: blob:"),
    );
    h.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
    r
}

fn error_response(e: &ApiError) -> Response {
    let status = StatusCode::from_u16(e.status).unwrap_or(StatusCode::BAD_REQUEST);
    (status, Json(e.body())).into_response()
}

async fn fit_handler(State(state): State<Arc<AppState>>, req: Request<Body>) -> Response {
    let started = Instant::now();
    // Uploads have a cap of their own, so that slow clients sending their
    // bodies cannot hold the fit slots that others need.
    let Ok(upload) = Arc::clone(&state.uploads).try_acquire_owned() else {
        return error_response(&ApiError::new(
            503,
            "too many requests in flight (--max-in-flight); try again",
        ));
    };
    let outcome = tokio::time::timeout(state.timeout, fit_request(&state, req, upload)).await;
    let result = outcome.unwrap_or_else(|_| {
        Err(ApiError::new(
            504,
            format!(
                "the request took longer than {} ms (--timeout-ms)",
                state.timeout.as_millis()
            ),
        ))
    });
    match result {
        Ok((mut value, n, fit_ms)) => {
            if !state.quiet {
                let build_ms = value["build_ms"].as_f64().unwrap_or(f64::NAN);
                eprintln!(
                    "fit: {n} points, {build_ms:.3} ms building, {fit_ms:.3} ms with the JSON, {:.3} ms in total",
                    started.elapsed().as_secs_f64() * 1e3
                );
            }
            value["fit_ms"] = serde_json::json!(fit_ms);
            Json(value).into_response()
        }
        Err(e) => {
            if !state.quiet {
                eprintln!("fit refused ({}): {}", e.status, e.message);
            }
            error_response(&e)
        }
    }
}

/// Reads, checks and fits one request: the fit JSON, the number of points and
/// the milliseconds spent computing.
async fn fit_request(
    state: &AppState,
    req: Request<Body>,
    upload: tokio::sync::OwnedSemaphorePermit,
) -> Result<(serde_json::Value, usize, f64), ApiError> {
    let too_large = || {
        ApiError::new(
            413,
            format!("the body exceeds {} bytes (--max-body)", state.max_body),
        )
    };
    let declared = req
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok());
    if declared.is_some_and(|n| n > state.max_body as u64) {
        return Err(too_large());
    }
    let body = to_bytes(req.into_body(), state.max_body)
        .await
        .map_err(|_| too_large())?;
    drop(upload);
    // The fit slot is taken once the body is in.
    let Ok(permit) = Arc::clone(&state.in_flight).try_acquire_owned() else {
        return Err(ApiError::new(
            503,
            "too many requests in flight (--max-in-flight); try again",
        ));
    };
    let request = api::parse(&body, state.limits)?;
    let n = request.spec.points.len() / request.spec.dim.max(1);
    let task = tokio::task::spawn_blocking(move || {
        let _permit = permit;
        let t = Instant::now();
        let result = api::fit(&request);
        (result, t.elapsed())
    });
    match task.await {
        Ok((result, compute)) => result.map(|v| (v, n, compute.as_secs_f64() * 1e3)),
        Err(_) => Err(ApiError::new(500, "the fit stopped unexpectedly")),
    }
}
