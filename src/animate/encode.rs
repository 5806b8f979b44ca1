//! A GIF frame as what changed since the previous one: the rectangle of changed pixels,
//! the unchanged ones transparent.

use super::palette::TRANSPARENT;
use std::borrow::Cow;

/// The GIF frame of `now` after `before`: the rectangle of the pixels that changed, those
/// that did not transparent (the first frame whole).
pub(super) fn changed_frame<'a>(
    before: Option<&[u8]>,
    now: &'a [u8],
    w: usize,
    h: usize,
    delay: u16,
) -> gif::Frame<'a> {
    let whole = |buffer: Cow<'a, [u8]>, transparent| gif::Frame {
        delay,
        dispose: gif::DisposalMethod::Keep,
        transparent,
        width: w as u16,
        height: h as u16,
        buffer,
        ..gif::Frame::default()
    };
    let Some(before) = before else {
        return whole(Cow::Borrowed(now), None);
    };
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
    for y in 0..h {
        let row = y * w;
        for x in 0..w {
            if before[row + x] != now[row + x] {
                x0 = x0.min(x);
                x1 = x1.max(x + 1);
                y0 = y0.min(y);
                y1 = y1.max(y + 1);
            }
        }
    }
    if x1 <= x0 {
        // Nothing changed: one transparent pixel carries the delay.
        return gif::Frame {
            width: 1,
            height: 1,
            buffer: Cow::Owned(vec![TRANSPARENT]),
            ..whole(Cow::Borrowed(&[]), Some(TRANSPARENT))
        };
    }
    let mut buffer = Vec::with_capacity((x1 - x0) * (y1 - y0));
    for y in y0..y1 {
        for x in x0..x1 {
            let i = y * w + x;
            buffer.push(if before[i] == now[i] {
                TRANSPARENT
            } else {
                now[i]
            });
        }
    }
    gif::Frame {
        left: x0 as u16,
        top: y0 as u16,
        width: (x1 - x0) as u16,
        height: (y1 - y0) as u16,
        ..whole(Cow::Owned(buffer), Some(TRANSPARENT))
    }
}
