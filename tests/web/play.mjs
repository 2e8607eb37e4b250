// Plays the demo's page in Debian's Chromium, headless with software WebGL2 (SwiftShader).
// Loads each URL in turn in the same browser (so what one leaves in IndexedDB, the next finds:
// a reload), prints the page's console as it comes, and waits until the game reports its exit
// (Module.fluidExit: a scripted run ends after its frames) or TIMEOUT seconds. After the last,
// saves a screenshot of the page and copies files out of the page's file system. Exits with the
// first failing game's status (3 on a timeout, 4 when the page failed), else 0.
//
//   node tests/web/play.mjs [options] SCREENSHOT.png URL [URL ...]
//     --timeout S          seconds to wait for each game (default 600)
//     --frames-drawn N     wait until the game has drawn N frames (Module.fluidFramesDrawn)
//                          instead of its exit: a screenshot of a level being played
//     --copy FROM:TO       after the last URL, copy the page's file FROM to TO (repeatable)
//     --viewport WxH       the page's size in CSS pixels (default 1300x820)
//     --touch FX,FY ...    in the first URL, once the game runs: one finger down at the first
//                          point, moved through the others (0.15 s apart), lifted; points as
//                          fractions of the canvas. Prints each point's pixel in the game's
//                          1280 x 720 picture: "play.mjs: touch X Y".
import fs from 'node:fs';
import puppeteer from 'puppeteer-core';

const usage = 'usage: node play.mjs [--timeout S] [--frames-drawn N] [--copy FROM:TO] ' +
              '[--viewport WxH] ' +
              '[--touch "FX,FY FX,FY ..."] SCREENSHOT.png URL [URL ...]';
let timeout = 600 * 1000;
let viewport = {width: 1300, height: 820};
let touch = [];
let framesDrawn = 0;
const copies = [];
const positional = [];
const args = process.argv.slice(2);
for (let i = 0; i < args.length; ++i) {
  const value = args[i + 1];
  if (args[i] === '--timeout') {
    timeout = Number(value) * 1000;
    ++i;
  } else if (args[i] === '--frames-drawn') {
    framesDrawn = Number(value);
    ++i;
  } else if (args[i] === '--copy') {
    copies.push(value.split(':'));
    ++i;
  } else if (args[i] === '--viewport') {
    const [width, height] = value.split('x').map(Number);
    viewport = {width, height};
    ++i;
  } else if (args[i] === '--touch') {
    touch = value.trim().split(/\s+/).map((point) => point.split(',').map(Number));
    ++i;
  } else {
    positional.push(args[i]);
  }
}
const [screenshot, ...urls] = positional;
if (!screenshot || urls.length === 0 || !(timeout > 0) || !(viewport.width > 0) ||
    !(Number.isInteger(framesDrawn) && framesDrawn >= 0) ||
    touch.some((p) => p.length !== 2 || p.some((f) => !(f >= 0 && f <= 1)))) {
  console.error(usage);
  process.exit(2);
}
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// One finger through `points` (fractions of the canvas), once the game has started.
async function drag(page, points) {
  await page.waitForFunction('typeof Module !== "undefined" && Module.calledRun === true',
                             {timeout, polling: 50});
  const box = await page.evaluate(() => {
    const rect = document.getElementById('canvas').getBoundingClientRect();
    return {left: rect.left, top: rect.top, width: rect.width, height: rect.height};
  });
  const at = points.map(([fx, fy]) => {
    const x = Math.round(box.left + fx * box.width);
    const y = Math.round(box.top + fy * box.height);
    // Where the game sees it: the canvas's 1280 x 720 pixels, scaled from its CSS size.
    console.log('play.mjs: touch ' + ((x - box.left) * 1280 / box.width).toFixed(2) + ' ' +
                ((y - box.top) * 720 / box.height).toFixed(2));
    return [x, y];
  });
  await page.touchscreen.touchStart(at[0][0], at[0][1]);
  for (const [x, y] of at.slice(1)) {
    await sleep(150);
    await page.touchscreen.touchMove(x, y);
  }
  await sleep(150);
  await page.touchscreen.touchEnd();
}

const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
         `--window-size=${viewport.width},${viewport.height}`, '--disable-dev-shm-usage'],
});
let status = 0;
try {
  const page = await browser.newPage();
  await page.setViewport({...viewport, hasTouch: touch.length > 0});
  page.on('console', (message) => console.log(message.text()));
  page.on('pageerror', (error) => console.log('page error: ' + error.message));
  for (const [index, url] of urls.entries()) {
    let own = 4;
    await page.goto(url, {waitUntil: 'load'});
    try {
      if (index === 0 && touch.length > 0) {
        await drag(page, touch);
      }
      if (framesDrawn > 0) {
        await page.waitForFunction(
            `window.fluidExitCode !== undefined || (typeof Module !== 'undefined' && ` +
            `(Module.fluidFramesDrawn ?? 0) >= ${framesDrawn})`, {timeout, polling: 100});
        own = (await page.evaluate('window.fluidExitCode')) ?? 0;
      } else {
        await page.waitForFunction('window.fluidExitCode !== undefined', {timeout, polling: 250});
        own = await page.evaluate('window.fluidExitCode');
      }
    } catch (e) {
      console.log('play.mjs: no exit after ' + timeout / 1000 + ' s (' + url + '): ' + e.message);
      own = 3;
    }
    if (status === 0) {
      status = own;
    }
  }
  await page.screenshot({path: screenshot});
  for (const [from, to] of copies) {
    const bytes = await page.evaluate((path) => {
      try {
        return Array.from(FS.readFile(path));
      } catch (e) {
        return null;
      }
    }, from);
    if (bytes === null) {
      console.log('play.mjs: the page has no ' + from);
      status = status === 0 ? 4 : status;
    } else {
      fs.writeFileSync(to, Buffer.from(bytes));
    }
  }
} catch (e) {
  console.log('play.mjs: ' + e.message);
  status = 4;
} finally {
  await browser.close();
}
process.exit(status);
