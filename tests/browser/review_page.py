#!/usr/bin/env python3
"""Drives the page of `bcot review` in headless Chromium through the DevTools protocol over a
pipe (--remote-debugging-pipe; Python's standard library only, no driver or npm package).

  review_page.py CHROMIUM URL FRAME SCREENSHOT_DIR

Opens URL, waits until the page has shown frame 0 with every image loaded, clicks the timeline
at FRAME, and checks that the page then shows FRAME (number, slider, every view's image loaded
at the camera's size); then → moves to FRAME + 1 and, when the page lists bad frames, clicking
the first one shows it; with an annotation, the trajectory charts hold their series, a click on
the rotation chart shows frame 0, the mask box loads the tinted images, and a nudge of frame 0
set as its keyframe writes keyframes.txt. Any console message or script exception is a failure (the page logs
nothing). Screenshots go to SCREENSHOT_DIR. Prints one line per check; exit 0 when all pass.
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
        for kind in ('mousePressed', 'mouseReleased'):
            self.send('Input.dispatchMouseEvent', {'type': kind, 'x': x, 'y': y,
                                                   'button': 'left', 'clickCount': 1})

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


def run(binary, url, frame, shots):
    with tempfile.TemporaryDirectory() as profile:
        browser = Chromium(binary, profile)
        try:
            browser.open(url)
            browser.wait_for("document.body?.dataset.ready === 'yes'", 'the page to start')
            # The page opens at the frame the address names (bcot review --frame N), else 0.
            expect_frame(browser, int(url.split('#frame=')[1]) if '#frame=' in url else 0)
            # Click the timeline where it draws `frame`.
            x, y = browser.evaluate(f"""(() => {{
                const rect = document.getElementById('timeline').getBoundingClientRect();
                return [rect.left + timelineScale().x({frame}), rect.top + rect.height / 2];
            }})()""")
            browser.click(x, y)
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
                paths = browser.evaluate("""[
                    document.querySelectorAll('#rotation path').length,
                    document.querySelectorAll('#translation path').length]""")
                assert paths == [1, 3], f'trajectory charts hold {paths} series, not [1, 3]'
                # Click the rotation chart where it draws frame 0.
                x, y = browser.evaluate("""(() => {
                    const svg = document.getElementById('rotation');
                    svg.scrollIntoView({block: 'center'});
                    const rect = svg.getBoundingClientRect();
                    return [rect.left + timelineScale(svg).x(0), rect.top + rect.height / 2];
                })()""")
                browser.click(x, y)
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
            browser.screenshot(os.path.join(shots, 'review_end.png'))
            problems = browser.problems()
            assert not problems, f'console messages or exceptions: {problems}'
            print('ok: no console messages')
        finally:
            browser.close()


def main():
    if len(sys.argv) != 5:
        print(__doc__, file=sys.stderr)
        return 2
    binary, url, frame, shots = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    try:
        run(binary, url, frame, shots)
    except (AssertionError, RuntimeError, OSError) as error:
        print(f'FAILED: {error}')
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
