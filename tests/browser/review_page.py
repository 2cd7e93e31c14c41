#!/usr/bin/env python3
"""Drives the page of `bcot review` in headless Chromium through the DevTools protocol over a
pipe (--remote-debugging-pipe; Python's standard library only, no driver or npm package).

  review_page.py CHROMIUM URL FRAME SCREENSHOT_DIR [CAM:X,Y;CAM:X,Y]

Opens URL, waits until the page has shown frame 0 with every image loaded, clicks the timeline
at FRAME (without an annotation, which has no timeline, goes there by keys), and checks that the
page then shows FRAME (number, slider, every view's image loaded at the camera's size); then →
moves to FRAME + 1 and, when the page lists bad frames, clicking the first one shows it; with an
annotation, the trajectory charts hold their series, a click on the rotation chart shows frame
0, the mask box loads the tinted images, a nudge of frame 0 set as its keyframe writes
keyframes.txt, re-annotating around it from the page runs to the end and drops the edit, and
with "drag edits the pose" a drag and the wheel on a view move the pose.
With clicks (last argument; image pixels of frame 0), on a sequence without annotation: the
clicks on the views, "find pose", the first candidate drawn and saved as init_pose.txt, and
when the server has a directory to annotate into, "annotate" and the page of the result.
Any console message or script exception is a failure (the page logs nothing). Screenshots go to
SCREENSHOT_DIR. Prints one line per check; exit 0 when all pass.
"""
import base64
import fcntl
import json
import os
import subprocess
import sys
import tempfile
import time


class Chromium:
    """Headless Chromium with the DevTools protocol on fds 3 (commands in) and 4 (out)."""

    def __init__(self, binary, profile):
        to_chrome_read, self._write = (self._high(fd) for fd in os.pipe())
        self._read, from_chrome_write = (self._high(fd) for fd in os.pipe())

        def wire_pipes():
            os.dup2(to_chrome_read, 3)
            os.dup2(from_chrome_write, 4)

        self._log = open(os.path.join(profile, 'chromium.log'), 'wb')
        self._process = subprocess.Popen(
            [binary, '--headless', '--no-sandbox', '--disable-gpu', '--no-first-run',
             '--disable-background-networking', '--disable-component-update', '--disable-sync',
             '--remote-debugging-pipe', '--user-data-dir=' + os.path.join(profile, 'profile'),
             '--window-size=1200,1000', 'about:blank'],
            stdin=subprocess.DEVNULL, stdout=self._log, stderr=self._log,
            preexec_fn=wire_pipes, pass_fds=(3, 4))
        os.close(to_chrome_read)
        os.close(from_chrome_write)
        self._next_id = 0
        self._buffer = b''
        self.events = []
        self.session = None

    @staticmethod
    def _high(fd):
        """`fd` moved above the standard and DevTools descriptors (0..4)."""
        high = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
        os.close(fd)
        return high

    def _message(self):
        while b'\0' not in self._buffer:
            chunk = os.read(self._read, 1 << 16)
            if not chunk:
                raise RuntimeError('chromium closed the DevTools pipe')
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b'\0', 1)
        return json.loads(message)

    def send(self, method, params=None, session=True):
        self._next_id += 1
        command = {'id': self._next_id, 'method': method, 'params': params or {}}
        if session and self.session:
            command['sessionId'] = self.session
        os.write(self._write, json.dumps(command).encode() + b'\0')
        while True:
            message = self._message()
            if message.get('id') == self._next_id:
                if 'error' in message:
                    raise RuntimeError(f'{method}: {message["error"]}')
                return message.get('result', {})
            self.events.append(message)

    def open(self, url):
        target = self.send('Target.createTarget', {'url': 'about:blank'}, session=False)
        self.session = self.send('Target.attachToTarget',
                                 {'targetId': target['targetId'], 'flatten': True},
                                 session=False)['sessionId']
        self.send('Runtime.enable')
        self.send('Page.enable')
        self.send('Page.navigate', {'url': url})

    def evaluate(self, expression):
        result = self.send('Runtime.evaluate', {'expression': expression, 'returnByValue': True,
                                                'awaitPromise': True})
        if 'exceptionDetails' in result:
            raise RuntimeError(f'{expression}: {result["exceptionDetails"]}')
        return result['result'].get('value')

    def wait_for(self, expression, what, attempts=600):
        """Polls `expression` every 0.1 s until it is true (at most `attempts` times); while
        the page is still loading the expression may fail, which counts as not yet."""
        for _ in range(attempts):
            try:
                if self.evaluate(expression):
                    return
            except RuntimeError:
                pass
            time.sleep(0.1)
        raise RuntimeError(f'timed out waiting for {what} ({expression})')

    def click(self, x, y):
        """Moves the pointer to (x, y) and clicks there, as a hand does (charts track the
        pointer's moves)."""
        self.send('Input.dispatchMouseEvent', {'type': 'mouseMoved', 'x': x, 'y': y})
        time.sleep(0.2)  # a hand rests before it presses; the charts update on the move
        for kind in ('mousePressed', 'mouseReleased'):
            self.send('Input.dispatchMouseEvent', {'type': kind, 'x': x, 'y': y,
                                                   'button': 'left', 'clickCount': 1})

    def drag(self, x0, y0, x1, y1):
        """Presses at (x0, y0), moves to (x1, y1) in steps and releases there."""
        self.send('Input.dispatchMouseEvent', {'type': 'mouseMoved', 'x': x0, 'y': y0})
        self.send('Input.dispatchMouseEvent', {'type': 'mousePressed', 'x': x0, 'y': y0,
                                               'button': 'left', 'clickCount': 1})
        for k in range(1, 6):
            self.send('Input.dispatchMouseEvent', {
                'type': 'mouseMoved', 'x': x0 + (x1 - x0) * k / 5, 'y': y0 + (y1 - y0) * k / 5,
                'button': 'left', 'buttons': 1})
        self.send('Input.dispatchMouseEvent', {'type': 'mouseReleased', 'x': x1, 'y': y1,
                                               'button': 'left', 'clickCount': 1})

    def wheel(self, x, y, delta_y):
        self.send('Input.dispatchMouseEvent', {'type': 'mouseWheel', 'x': x, 'y': y,
                                               'deltaX': 0, 'deltaY': delta_y})

    def key(self, key, code):
        for kind in ('rawKeyDown', 'keyUp'):
            self.send('Input.dispatchKeyEvent', {'type': kind, 'key': key, 'code': key,
                                                 'windowsVirtualKeyCode': code})

    def screenshot(self, path):
        data = self.send('Page.captureScreenshot', {'format': 'png'})['data']
        with open(path, 'wb') as out:
            out.write(base64.b64decode(data))

    def problems(self):
        """Console messages and uncaught exceptions seen so far."""
        return [e for e in self.events
                if e.get('method') in ('Runtime.consoleAPICalled', 'Runtime.exceptionThrown')]

    def close(self):
        try:
            self.send('Browser.close', session=False)
        except (RuntimeError, OSError):
            pass
        try:
            self._process.wait(timeout=30)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()
        self._log.close()


def click_element(browser, selector):
    """Scrolls the element `selector` into view and clicks its centre."""
    x, y = browser.evaluate(f"""(() => {{
        const element = document.querySelector('{selector}');
        element.scrollIntoView({{block: 'center'}});
        const rect = element.getBoundingClientRect();
        return [rect.left + rect.width / 2, rect.top + rect.height / 2];
    }})()""")
    browser.click(x, y)


def expect_frame(browser, frame):
    """The page shows `frame` with every view's image loaded at its camera's size."""
    browser.wait_for(f"document.body.dataset.loadedFrame === '{frame}'", f'frame {frame}')
    shown = browser.evaluate("""({
        number: document.getElementById('frame-number').textContent,
        slider: document.getElementById('slider').value,
        images: [...document.querySelectorAll('#views img')].map((img) => ({
            src: img.getAttribute('src'), width: img.naturalWidth,
            expected: state.sequence.cameras.find((c) => c.name === img.dataset.camera).width}))
    })""")
    assert shown['number'] == str(frame), f'frame number shows {shown["number"]}, not {frame}'
    assert shown['slider'] == str(frame), f'slider at {shown["slider"]}, not {frame}'
    assert shown['images'], 'no view images on the page'
    for image in shown['images']:
        assert f'/frame/{frame}/' in image['src'], f'{image["src"]} is not of frame {frame}'
        assert image['width'] == image['expected'], f'{image["src"]} did not load: {image}'
    print(f'ok: frame {frame} shown, {len(shown["images"])} images loaded')


def click_chart(browser, chart, frame):
    """Clicks chart `chart` (a dygraph of the page) where it draws `frame`."""
    x, y = browser.evaluate(f"chartPoint('{chart}', {frame})")
    browser.click(x, y)


def click_image(browser, camera, x, y):
    """Clicks the view of `camera` at image pixel (x, y)."""
    px, py = browser.evaluate(f"""(() => {{
        const img = document.querySelector('#views img[data-camera="{camera}"]');
        img.scrollIntoView({{block: 'center'}});
        const rect = img.getBoundingClientRect();
        return [rect.left + {x} / img.naturalWidth * rect.width,
                rect.top + {y} / img.naturalHeight * rect.height];
    }})()""")
    browser.click(px, py)


def initialise(browser, clicks, shots):
    """The initialisation flow: clicks on frame 0's views, find pose, save the first candidate."""
    for click in clicks.split(';'):
        camera, xy = click.split(':')
        x, y = (float(v) for v in xy.split(','))
        click_image(browser, camera, x, y)
    shown = browser.evaluate("document.getElementById('init-clicks').textContent")
    assert shown.count(':') == len(clicks.split(';')), f'clicks shown: {shown}'
    click_element(browser, '#init-find')
    browser.wait_for("document.body.dataset.job === 'done' || "
                     "document.body.dataset.job === 'failed'", 'the pose search', 1800)
    status = browser.evaluate("document.getElementById('job-status').textContent")
    assert browser.evaluate("document.body.dataset.job") == 'done', f'search failed: {status}'
    candidates = int(browser.evaluate('document.body.dataset.initCandidates'))
    assert candidates >= 1, 'no candidates'
    browser.wait_for("[...document.querySelectorAll('#views img')].every("
                     "(img) => img.getAttribute('src').endsWith('?candidate=0'))",
                     'the candidate overlays')
    expect_frame(browser, 0)
    browser.screenshot(os.path.join(shots, 'review_init.png'))
    click_element(browser, '#init-save')
    browser.wait_for("document.body.dataset.initSaved", 'the saved pose')
    saved = browser.evaluate('document.body.dataset.initSaved')
    print(f'ok: initial pose from {len(clicks.split(";"))} clicks, {candidates} candidate(s), '
          f'saved to {saved}')
    if browser.evaluate('state.sequence.annotation_target !== null'):
        # Annotate from the page: it reloads as the page of the new annotation.
        click_element(browser, '#annotate')
        browser.wait_for("document.body.dataset.ready === 'yes' && state.sequence.contour && "
                         "state.quality.available", 'the page of the new annotation', 3000)
        expect_frame(browser, 0)
        browser.screenshot(os.path.join(shots, 'review_annotated.png'))
        print(f'ok: annotated from the page into {browser.evaluate("state.sequence.annotation")}')


def run(binary, url, frame, shots, clicks):
    with tempfile.TemporaryDirectory() as profile:
        browser = Chromium(binary, profile)
        try:
            browser.open(url)
            browser.wait_for("document.body?.dataset.ready === 'yes'", 'the page to start')
            # The page opens at the frame the address names (bcot review --frame N), else 0.
            expect_frame(browser, int(url.split('#frame=')[1]) if '#frame=' in url else 0)
            if clicks:
                initialise(browser, clicks, shots)
            if browser.evaluate("'timeline' in state.charts"):
                click_chart(browser, 'timeline', frame)
            else:
                browser.key('Home', 36)
                expect_frame(browser, 0)
                for _ in range(frame):
                    browser.key('ArrowRight', 39)
            expect_frame(browser, frame)
            browser.screenshot(os.path.join(shots, 'review_timeline_click.png'))
            browser.key('ArrowRight', 39)
            expect_frame(browser, frame + 1)
            bad = browser.evaluate('state.quality.available ? state.quality.bad_frames : []')
            if bad:
                click_element(browser, f'#bad-frames button[data-frame="{bad[0]}"]')
                expect_frame(browser, bad[0])
            print(f'ok: bad frames listed: {bad}')
            if browser.evaluate('state.trajectory.available'):
                series = browser.evaluate("""[
                    state.charts.rotation.numColumns() - 1,
                    state.charts.translation.numColumns() - 1]""")
                assert series == [1, 3], f'trajectory charts hold {series} series, not [1, 3]'
                click_chart(browser, 'rotation', 0)
                expect_frame(browser, 0)
                print('ok: trajectory charts drawn, a click on them shows the frame')
                click_element(browser, '#mask')
                browser.wait_for("[...document.querySelectorAll('#views img')].every("
                                 "(img) => img.getAttribute('src').endsWith('?mask=1'))",
                                 'the masked images')
                expect_frame(browser, 0)
                browser.screenshot(os.path.join(shots, 'review_mask.png'))
                print('ok: the mask box shows the tinted silhouettes')

                click_element(browser, '[data-nudge="dx:1"]')
                browser.wait_for("document.body.dataset.edits === '1'", 'the nudge')
                expect_frame(browser, 0)
                click_element(browser, '#keyframe')
                browser.wait_for("document.body.dataset.keyframe === '0'", 'the keyframe')
                browser.screenshot(os.path.join(shots, 'review_edit.png'))
                print('ok: nudged frame 0 and set it as keyframe 0')

                span = browser.evaluate("[document.getElementById('reannotate-first').value, "
                                        "document.getElementById('reannotate-last').value]")
                click_element(browser, '#reannotate')
                browser.wait_for("document.body.dataset.job === 'done' || "
                                 "document.body.dataset.job === 'failed'", 're-annotation', 1800)
                status = browser.evaluate("document.getElementById('job-status').textContent")
                assert browser.evaluate('document.body.dataset.job') == 'done', status
                browser.wait_for("document.body.dataset.edits === '0'", 'the edit dropped')
                expect_frame(browser, 0)
                browser.screenshot(os.path.join(shots, 'review_reannotated.png'))
                print(f'ok: re-annotated frames {span[0]}:{span[1]} from the page: {status}')
                # The timeline shows the new errors (the caller compares them with quality.json).
                errors = browser.evaluate(
                    "state.quality.views.map((v) => v.name + '=' + v.error_px[0]).join(' ')")
                print(f'timeline frame 0 after re-annotation: {errors}')

                # With "drag edits the pose": a drag on cam0 moves the model, the wheel its depth.
                click_element(browser, '#edit-drag')
                before = browser.evaluate("fetch('api/frame/0/pose').then((r) => r.json())")
                x, y = browser.evaluate("""(() => {
                    const img = document.querySelector('#views img');
                    img.scrollIntoView({block: 'center'});
                    const rect = img.getBoundingClientRect();
                    return [rect.left + rect.width / 2, rect.top + rect.height / 2];
                })()""")
                browser.drag(x, y, x + 40, y)
                browser.wait_for("document.body.dataset.edits === '1'", 'the drag edit')
                browser.wheel(x, y, 100)
                browser.wait_for("document.body.dataset.edits === '2'", 'the wheel edit')
                after = browser.evaluate("fetch('api/frame/0/pose').then((r) => r.json())")
                moved = [a - b for a, b in zip(after['rig_from_object'][9:],
                                               before['rig_from_object'][9:])]
                assert any(abs(m) > 0.1 for m in moved), f'the pose did not move: {moved}'
                expect_frame(browser, 0)
                print(f'ok: a drag and the wheel on a view moved the pose by {moved} mm')
                # The edit keys: d moves right (a nudge), u undoes it.
                browser.key('d', 68)
                browser.wait_for("document.body.dataset.edits === '3'", 'the key edit')
                browser.key('u', 85)
                browser.wait_for("document.body.dataset.edits === '2'", 'the key undo')
                expect_frame(browser, 0)
                print('ok: the edit keys nudge and undo')
            browser.screenshot(os.path.join(shots, 'review_end.png'))
            problems = browser.problems()
            assert not problems, f'console messages or exceptions: {problems}'
            print('ok: no console messages')
        finally:
            browser.close()


def main():
    if len(sys.argv) not in (5, 6):
        print(__doc__, file=sys.stderr)
        return 2
    binary, url, frame, shots = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    clicks = sys.argv[5] if len(sys.argv) == 6 else ''
    try:
        run(binary, url, frame, shots, clicks)
    except (AssertionError, RuntimeError, OSError) as error:
        print(f'FAILED: {error}')
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
