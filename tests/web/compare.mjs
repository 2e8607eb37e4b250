// Compares two pictures of the game (PNG, the same size) in Debian's Chromium: the share of
// pixels whose colour differs by more than THRESHOLD in some channel, outside the HUD's corner
// (its frame rate and timings differ between machines). Prints the share; exits 1 when it is
// above MAX_SHARE, 2 for bad arguments or pictures of different sizes.
//
//   node tests/web/compare.mjs A.png B.png [MAX_SHARE] [THRESHOLD]
import fs from 'node:fs';
import puppeteer from 'puppeteer-core';

const [a, b, maxText, thresholdText] = process.argv.slice(2);
if (!a || !b) {
  console.error('usage: node compare.mjs A.png B.png [MAX_SHARE] [THRESHOLD]');
  process.exit(2);
}
const maxShare = Number(maxText ?? 0.01);
const threshold = Number(thresholdText ?? 48);
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-dev-shm-usage'],
});
let result;
try {
  const page = await browser.newPage();
  const urls = [a, b].map((f) => 'data:image/png;base64,' + fs.readFileSync(f).toString('base64'));
  result = await page.evaluate(async ([urlA, urlB, limit]) => {
    const pixels = async (src) => {
      const image = new Image();
      image.src = src;
      await image.decode();
      const canvas = new OffscreenCanvas(image.width, image.height);
      const context = canvas.getContext('2d');
      context.drawImage(image, 0, 0);
      return {w: image.width, h: image.height,
              data: context.getImageData(0, 0, image.width, image.height).data};
    };
    const [p, q] = [await pixels(urlA), await pixels(urlB)];
    if (p.w !== q.w || p.h !== q.h) {
      return {error: `sizes differ: ${p.w}x${p.h} and ${q.w}x${q.h}`};
    }
    // The HUD's box: the top left 300 x 140 px (docs/demo.md).
    let differ = 0, counted = 0;
    for (let y = 0; y < p.h; ++y) {
      for (let x = 0; x < p.w; ++x) {
        if (x < 300 && y < 140) {
          continue;
        }
        const i = 4 * (y * p.w + x);
        ++counted;
        if (Math.abs(p.data[i] - q.data[i]) > limit || Math.abs(p.data[i + 1] - q.data[i + 1]) > limit ||
            Math.abs(p.data[i + 2] - q.data[i + 2]) > limit) {
          ++differ;
        }
      }
    }
    return {share: differ / counted, differ, counted};
  }, [urls[0], urls[1], threshold]);
} finally {
  await browser.close();
}
if (result.error) {
  console.log('compare: ' + result.error);
  process.exit(2);
}
console.log(`compare: ${result.differ} of ${result.counted} pixels differ by more than ` +
            `${threshold} (${(100 * result.share).toFixed(3)}%, at most ${100 * maxShare}%)`);
process.exit(result.share <= maxShare ? 0 : 1);
