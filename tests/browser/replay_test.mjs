// Opens an HTML replay in headless Chromium and checks it: it renders without console errors,
// page errors or network requests, every layer toggle redraws cleanly, play advances the
// timeline, and moving the timeline slider moves the robot's drawn position; in a footstep
// (humanoid) replay the taken feet drawn grow from the two start feet to all of them.
// Usage: node replay_test.mjs REPLAY.html [SCREENSHOT.png]   (CHROMIUM=path overrides /usr/bin/chromium)
import { chromium } from "playwright-core";
import { pathToFileURL } from "node:url";

const [file, screenshot] = process.argv.slice(2);
if (!file) {
  console.error("usage: node replay_test.mjs REPLAY.html [SCREENSHOT.png]");
  process.exit(2);
}
const problems = [];
const check = (ok, what) => {
  console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
  if (!ok) problems.push(what);
};

const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || "/usr/bin/chromium" });
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.on("console", (m) => m.type() === "error" && problems.push(`console error: ${m.text()}`));
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("request", (r) => /^(file|data|blob):/.test(r.url()) || problems.push(`network request: ${r.url()}`));

  await page.goto(pathToFileURL(file).href);
  await page.waitForFunction(() => window.replay && window.replay.ready, null, { timeout: 60000 });
  const status = await page.textContent("#status");
  check(status === "", `page loaded (status "${status}")`);
  const frames = Number(await page.getAttribute("#slider", "max")) + 1;
  check(frames >= 10, `${frames} frames on the timeline`);

  const seek = async (i) => {
    await page.locator("#slider").fill(String(i));
    await page.waitForFunction((v) => window.replay.frame === v, i, { timeout: 10000 });
    return page.evaluate(() => window.replay.robotScreen);
  };
  const a = await seek(0);
  const b = await seek(frames - 1);
  const moved = Math.hypot(a[0] - b[0], a[1] - b[1]);
  check(moved > 10, `moving the slider moves the drawn robot by ${moved.toFixed(1)} px`);
  const attr = await page.getAttribute("#world", "data-robot-x");
  check(Math.abs(Number(attr) - b[0]) < 0.2, "the canvas exposes the robot's drawn position");

  // Footstep (humanoid) replays: the footstep layers are listed and the taken feet grow with time.
  const taken = await page.evaluate(() => {
    const fs = JSON.parse(document.getElementById("replay-data").textContent).footsteps;
    return fs ? fs.taken.length : null;
  });
  if (taken !== null) {
    check((await page.locator("#layer-footTaken").count()) === 1, "the footstep layers are listed");
    check((await page.locator("#layer-lidar").count()) === 0, "the wheeled-only layers are not");
    const last = await page.evaluate(() => window.replay.feetTaken);
    await seek(0);
    const first = await page.evaluate(() => window.replay.feetTaken);
    check(first === 2 && last === taken, `feet drawn: ${first} at the start, ${last} of ${taken} at the end`);
    await seek(frames - 1);
  }

  const inked = await page.evaluate(() => {
    const c = document.getElementById("world");
    const px = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < px.length; i += 4) n += px[i] < 250 || px[i + 1] < 250 || px[i + 2] < 250;
    return n;
  });
  check(inked > 2000, `the map canvas is drawn (${inked} non-white pixels)`);

  for (const box of await page.locator("#layers input").all()) {
    await box.click();
    await page.waitForTimeout(30);
    await box.click();
  }
  await page.waitForTimeout(100);
  check(true, "every layer toggled off and on");

  await seek(0);
  await page.selectOption("#speed", "8");
  await page.click("#play");
  await page.waitForFunction(() => window.replay.frame > 5, null, { timeout: 10000 });
  await page.click("#play");
  check(true, "play advances the timeline");

  if (screenshot) {
    await seek(Math.floor(frames * 0.6));
    await page.screenshot({ path: screenshot });
    console.log(`screenshot: ${screenshot}`);
  }
} catch (err) {
  problems.push(`exception: ${err.message}`);
} finally {
  await browser.close();
}
if (problems.length) {
  console.error(problems.join("\n"));
  process.exit(1);
}
console.log("replay OK");
