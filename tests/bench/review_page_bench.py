#!/usr/bin/env python3
"""The frame switch of `bcot review`'s page as a user sees it, in headless Chromium: from the
page's showFrame(N) (what the slider, the arrow keys and the charts call) until every view's
image of frame N has loaded (the page's data-loaded-frame), including the server's work (read,
Embree contour, JPEG), the transfer, the decode and the charts' redraw.

  review_page_bench.py CHROMIUM URL SWITCHES

Steps through SWITCHES frames (one frame at a time, then jumps of a third of the sequence), each
after the previous has loaded, and prints one line per kind of switch: count, median, p90 and
max milliseconds. Uses the DevTools driver of tests/browser/review_page.py.
"""
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'browser'))
from review_page import Chromium  # noqa: E402

TIME_SWITCH = """(async (frame) => {
    const start = performance.now();
    showFrame(frame);
    while (document.body.dataset.loadedFrame !== String(frame)) {
        await new Promise((resolve) => setTimeout(resolve, 1));
    }
    return performance.now() - start;
})(%d)"""


def quantile(values, q):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def main():
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    binary, url, switches = sys.argv[1], sys.argv[2], int(sys.argv[3])
    with tempfile.TemporaryDirectory() as profile:
        browser = Chromium(binary, profile)
        try:
            browser.open(url)
            browser.wait_for("document.body?.dataset.ready === 'yes'", 'the page to start')
            browser.wait_for("document.body.dataset.loadedFrame === '0'", 'frame 0')
            count = browser.evaluate('state.sequence.num_frames')
            views = browser.evaluate('state.sequence.cameras.length')
            size = browser.evaluate("state.sequence.cameras.map((c) => c.width + '×' + "
                                    "c.height).join(', ')")
            times = {'next frame (→)': [], 'jump (a third of the sequence)': []}
            frame = 0
            for k in range(switches):
                frame = (frame + 1) % count
                times['next frame (→)'].append(browser.evaluate(TIME_SWITCH % frame))
            for k in range(switches):
                frame = (frame + max(1, count // 3)) % count
                times['jump (a third of the sequence)'].append(browser.evaluate(TIME_SWITCH % frame))
            problems = browser.problems()
        finally:
            browser.close()
    print(f'{views} views ({size}), {count} frames; Chromium headless, one page')
    print('| switch | count | median ms | p90 ms | max ms |')
    print('|---|---:|---:|---:|---:|')
    for kind, values in times.items():
        print(f'| {kind} | {len(values)} | {statistics.median(values):.1f} | '
              f'{quantile(values, 0.9):.1f} | {max(values):.1f} |')
    if problems:
        print(f'console messages or exceptions: {problems}', file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
