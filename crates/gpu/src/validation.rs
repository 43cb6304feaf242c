//! Validation of created pipelines through wgpu's error scopes, on every target. A native
//! device answers a scope at once, so [`validated`] blocks on it there and returns the
//! error as a value. A browser's WebGPU answers only from its event loop, which a blocking
//! wait would never let run (it panics: "condvar wait not supported"); there [`validated`]
//! keeps the scope's answer pending, [`pending_errors`] reports one that has arrived (the
//! renderers call it before each frame's work), and [`settle`] awaits them all (the
//! renderers' async constructors call it, so they return only validated pipelines).

use std::future::Future;

use super::GpuError;

/// `object` if the error `scope` (pushed before creating it) caught nothing; `what` names
/// the object in the error. On WebAssembly the check is left pending (see the module doc).
pub fn validated<P>(
    scope: wgpu::ErrorScopeGuard,
    what: impl FnOnce() -> String,
    object: P,
) -> Result<P, GpuError> {
    #[cfg(not(target_family = "wasm"))]
    {
        match pollster::block_on(scope.pop()) {
            Some(e) => Err(validation_error(what(), &e)),
            None => Ok(object),
        }
    }
    #[cfg(target_family = "wasm")]
    {
        pending::push(what(), Box::pin(scope.pop()));
        Ok(object)
    }
}

/// Awaits the error `scope` (pushed before creating what `what` names).
pub async fn validated_async(
    scope: wgpu::ErrorScopeGuard,
    what: impl FnOnce() -> String,
) -> Result<(), GpuError> {
    match scope.pop().await {
        Some(e) => Err(validation_error(what(), &e)),
        None => Ok(()),
    }
}

/// The first validation error among the pending checks that have been answered (always
/// `Ok` on native targets, where no check is left pending).
pub fn pending_errors() -> Result<(), GpuError> {
    #[cfg(target_family = "wasm")]
    {
        pending::poll()
    }
    #[cfg(not(target_family = "wasm"))]
    {
        Ok(())
    }
}

/// Awaits every pending check and returns the first error (at once on native targets).
pub fn settle() -> impl Future<Output = Result<(), GpuError>> {
    #[cfg(target_family = "wasm")]
    {
        pending::settle()
    }
    #[cfg(not(target_family = "wasm"))]
    {
        std::future::ready(Ok(()))
    }
}

fn validation_error(what: String, e: &wgpu::Error) -> GpuError {
    GpuError::Validation {
        what,
        message: e.to_string(),
    }
}

/// The checks a browser has not answered yet, on the page's one thread.
#[cfg(target_family = "wasm")]
mod pending {
    use std::cell::RefCell;
    use std::future::Future;
    use std::pin::Pin;
    use std::task::{Context, Poll, Waker};

    use super::{GpuError, validation_error};

    type Answer = Pin<Box<dyn Future<Output = Option<wgpu::Error>>>>;

    thread_local! {
        static PENDING: RefCell<Vec<(String, Answer)>> = const { RefCell::new(Vec::new()) };
    }

    pub(super) fn push(what: String, answer: Answer) {
        PENDING.with(|p| p.borrow_mut().push((what, answer)));
    }

    /// Polls each pending answer once: the browser resolves them on its own, so a poll
    /// without a waker sees an answer as soon as it has come.
    pub(super) fn poll() -> Result<(), GpuError> {
        let mut first = None;
        PENDING.with(|p| {
            p.borrow_mut().retain_mut(|(what, answer)| {
                let mut cx = Context::from_waker(Waker::noop());
                match answer.as_mut().poll(&mut cx) {
                    Poll::Pending => true,
                    Poll::Ready(error) => {
                        if first.is_none()
                            && let Some(e) = error
                        {
                            first = Some(validation_error(std::mem::take(what), &e));
                        }
                        false
                    }
                }
            })
        });
        first.map_or(Ok(()), Err)
    }

    pub(super) async fn settle() -> Result<(), GpuError> {
        let all = PENDING.with(|p| std::mem::take(&mut *p.borrow_mut()));
        let mut first = Ok(());
        for (what, answer) in all {
            if let Some(e) = answer.await
                && first.is_ok()
            {
                first = Err(validation_error(what, &e));
            }
        }
        first
    }
}
