// Opens a `shoal view` HTML file from file:// in headless Chromium and checks it works:
// no console errors, no page errors, no request leaving the file (works offline), a WebGL
// canvas that is not blank, the plan's AUV colours in the legend, a time slider that changes the displayed step, and the play button;
// with a simulation (`shoal view --sim`), the layer toggles of the executed and estimated tracks.
// Saves a screenshot at the start (<shot>-start.png) and at mid-mission (<shot>).
//
//   node tests/viewer/check.mjs mission.html shot.png
//
// Chromium: $CHROMIUM, else /usr/bin/chromium (Debian's package `chromium`).
import { chromium } from 'playwright-core';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const [html, shot] = process.argv.slice(2);
if (!html || !shot) {
  console.error('usage: node check.mjs mission.html shot.png');
  process.exit(2);
}
const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
if (!existsSync(executablePath)) {
  console.error(`no Chromium at ${executablePath}: apt-get install -y --no-install-recommends chromium`);
  process.exit(2);
}

const problems = [];
const profile = mkdtempSync(join(tmpdir(), 'shoal-viewer-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath,
  headless: true,
  viewport: { width: 1400, height: 850 },
  args: [
    '--no-sandbox',
    '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader',
    '--disable-quic',
    '--no-first-run',
    '--disable-background-networking',
    '--disable-component-update',
    '--disable-sync',
  ],
});
const started = Date.now();
try {
  const page = browser.pages()[0] || (await browser.newPage());
  page.on('console', (m) => {
    if (m.type() === 'error') problems.push(`console error: ${m.text()}`);
    else if (m.type() === 'warning') console.log(`console warning: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('request', (r) => {
    if (!/^(file|blob|data):/.test(r.url())) problems.push(`network request: ${r.url()}`);
  });
  await page.goto(pathToFileURL(resolve(html)).href);
  await page.waitForFunction(() => window.shoalViewer?.ready || !document.getElementById('error').hidden,
    null, { timeout: 60000 });
  const error = await page.locator('#error').textContent();
  if (await page.locator('#error').isVisible()) throw new Error(`the page shows an error: ${error}`);

  // Let a few frames render, then look at the canvas pixels.
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const pixels = await page.evaluate(() => {
    const src = document.querySelector('#scene canvas');
    const c = document.createElement('canvas');
    [c.width, c.height] = [200, 120];
    const ctx = c.getContext('2d');
    ctx.drawImage(src, 0, 0, c.width, c.height);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    const colours = new Set();
    let differing = 0;
    for (let i = 0; i < d.length; i += 4) {
      colours.add((d[i] >> 3) << 10 | (d[i + 1] >> 3) << 5 | (d[i + 2] >> 3));
      if (Math.abs(d[i] - 11) + Math.abs(d[i + 1] - 22) + Math.abs(d[i + 2] - 38) > 24) differing++;
    }
    return { width: src.width, height: src.height, colours: colours.size, drawn: differing / (d.length / 4) };
  });
  console.log(`canvas ${pixels.width}×${pixels.height}: ${pixels.colours} colours, ${(100 * pixels.drawn).toFixed(1)} % not background`);
  if (pixels.colours < 30 || pixels.drawn < 0.1) problems.push(`the canvas looks blank: ${JSON.stringify(pixels)}`);

  // AUV colours: the legend shows the plan's (its figures' colours tinted by the planner, see
  // src/viewer/tests.rs), none near a link's colour (RGB distance ≥ 60 of 255).
  const swatches = await page.evaluate(() => {
    const data = JSON.parse(document.getElementById('plan-data').textContent);
    const hex = (c) => [1, 3, 5].map((i) => parseInt(c.slice(i, i + 2), 16));
    const css = (el) => getComputedStyle(el).backgroundColor.match(/\d+/g).slice(0, 3).map(Number);
    const links = [...document.querySelectorAll('#legend .bar')].map(css);
    const shown = [...document.querySelectorAll('#legend .swatch')].slice(1); // [0] is the USV
    return data.auv_colours.map((c, i) => {
      const rgb = shown[i] ? css(shown[i]) : null;
      const near = rgb ? Math.min(...links.map((l) => Math.hypot(...l.map((v, k) => v - rgb[k])))) : 0;
      return { i, want: hex(c), rgb, near };
    });
  });
  for (const { i, want, rgb, near } of swatches) {
    if (!rgb) problems.push(`no legend swatch for AUV ${i}`);
    else if (rgb.join() !== want.join()) problems.push(`AUV ${i}: legend colour ${rgb}, the plan's is ${want}`);
    else if (near < 60) problems.push(`AUV ${i}: its colour is ${near.toFixed(0)} from a link's colour`);
  }
  console.log(`legend: ${swatches.length} AUV colours as the plan gives them, none like a link's`);

  const before = await page.locator('#step-label').textContent();
  const steps = await page.evaluate(() => window.shoalViewer.steps);
  const startShot = shot.replace(/(\.png)?$/i, '-start.png');
  await page.screenshot({ path: startShot });

  // Move the slider to mid-mission.
  const mid = Math.floor((steps - 1) / 2) + 1;
  await page.locator('#step').fill(String(mid));
  const after = await page.locator('#step-label').textContent();
  const state = await page.evaluate(() => window.shoalViewer.step);
  console.log(`slider: "${before}" → "${after}"`);
  if (state !== mid) problems.push(`the slider set step ${state}, expected ${mid}`);
  if (after === before || !after.startsWith(`step ${mid} / ${steps - 1}`)) {
    problems.push(`the step label did not follow the slider: "${before}" → "${after}"`);
  }
  const links = await page.locator('#links li').count();
  if (links < 1) problems.push('no link listed at mid-mission');
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: shot });

  // With a simulation: the layer toggles hide and show the executed and estimated tracks, and
  // the AUV markers follow the executed track while it is shown.
  const sim = await page.evaluate(() => !!JSON.parse(document.getElementById('plan-data').textContent).sim);
  if (sim) {
    if (!(await page.locator('#layers').isVisible())) problems.push('the layer toggles are hidden');
    const marker = () => page.evaluate(() => {
      const v = window.shoalViewer.scene.vehicles.find((x) => x.auv === 0);
      return v.marker.position.toArray();
    });
    const visible = () => page.evaluate(() => {
      const t = window.shoalViewer.scene.tracks[0];
      return { executed: t.exec.visible, estimate: t.dots.visible };
    });
    const onTrack = await marker();
    for (const name of ['executed', 'estimate', 'planned']) {
      await page.locator(`#layer-${name}`).uncheck();
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(r)));
    }
    const hidden = await visible();
    if (hidden.executed || hidden.estimate) problems.push(`tracks still shown after unticking: ${JSON.stringify(hidden)}`);
    const onPlan = await marker();
    if (onTrack.every((v, i) => v === onPlan[i])) problems.push('the AUV marker did not leave the executed track');
    for (const name of ['executed', 'estimate', 'planned']) await page.locator(`#layer-${name}`).check();
    const shown = await visible();
    if (!shown.executed || !shown.estimate) problems.push(`tracks hidden after ticking: ${JSON.stringify(shown)}`);
    const back = await marker();
    if (back.some((v, i) => Math.abs(v - onTrack[i]) > 1e-6)) problems.push('the AUV marker did not return to the executed track');
    console.log(`layers: executed and estimated tracks toggled; marker ${onTrack.map((v) => v.toFixed(1))} on the track, ${onPlan.map((v) => v.toFixed(1))} on the plan`);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await page.screenshot({ path: shot });
  }

  // Play advances the step.
  await page.locator('#play').click();
  await page.waitForFunction((m) => window.shoalViewer.step > m, mid, { timeout: 10000 })
    .catch(() => problems.push('play did not advance the step'));
  await page.locator('#play').click();
  console.log(`screenshots: ${startShot}, ${shot}`);
} catch (e) {
  problems.push(`check failed: ${e.message}`);
} finally {
  await browser.close();
  rmSync(profile, { recursive: true, force: true });
}
console.log(`checked ${html} in ${((Date.now() - started) / 1000).toFixed(1)} s`);
if (problems.length) {
  for (const p of problems) console.error(`FAIL ${p}`);
  process.exit(1);
}
console.log('viewer OK');
