// Plays the demo's page in Debian's Chromium, headless with software WebGL2 (SwiftShader):
// loads URL, prints the page's console as it comes, waits until the game reports its exit
// (Module.fluidExit: a scripted run ends after its frames) or TIMEOUT seconds, saves a
// screenshot of the page, copies files out of the page's file system (FROM:TO pairs: a save,
// the game's own screenshot), and exits with the game's status (3 on a timeout, 4 when the
// page failed).
//
//   node tests/web/play.mjs URL SCREENSHOT.png [TIMEOUT] [FROM:TO ...]
import fs from 'node:fs';
import puppeteer from 'puppeteer-core';

const [url, screenshot, timeoutText, ...copies] = process.argv.slice(2);
if (!url || !screenshot) {
  console.error('usage: node play.mjs URL SCREENSHOT.png [TIMEOUT] [FROM:TO ...]');
  process.exit(2);
}
const timeout = Number(timeoutText ?? 600) * 1000;
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
         '--window-size=1300,820', '--disable-dev-shm-usage'],
});
let status = 4;
try {
  const page = await browser.newPage();
  await page.setViewport({width: 1300, height: 820});
  page.on('console', (message) => console.log(message.text()));
  page.on('pageerror', (error) => console.log('page error: ' + error.message));
  await page.goto(url, {waitUntil: 'load'});
  try {
    await page.waitForFunction('window.fluidExitCode !== undefined', {timeout, polling: 250});
    status = await page.evaluate('window.fluidExitCode');
  } catch (e) {
    console.log('play.mjs: no exit after ' + timeout / 1000 + ' s');
    status = 3;
  }
  await page.screenshot({path: screenshot});
  for (const pair of copies) {
    const [from, to] = pair.split(':');
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
} finally {
  await browser.close();
}
process.exit(status);
