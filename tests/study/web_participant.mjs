// A scripted participant for crowdlab's web study (export-web), in headless Chromium through the
// DevTools protocol (puppeteer-core, pointed at the system chromium). Used by tests/study/test_web.cpp.
//
// node web_participant.mjs WEBDIR CHROMIUM NODE_MODULES ANSWERS.json OUTDIR PARTICIPANT RELOAD_AFTER
//   serves WEBDIR on 127.0.0.1 (a tiny static server, no dependency), opens
//   index.html?participant=PARTICIPANT, answers every screen (answers: {stimulus: {question: raw}}),
//   reloads the page once after RELOAD_AFTER answered trials and checks that the study resumes at the
//   next trial, and writes to OUTDIR: download.json (the end screen's download), localstorage.json,
//   fnv.json (the page's FNV-1a of test strings), resume.json, jspsych-1.csv and jspsych-2.csv
//   (jsPsych.data.get().csv() before the reload and at the end), layout.json with likert-1920x1080.png
//   and likert-1440x900.png (the first Likert screen at both window sizes) and one screenshot per kind
//   of screen (at 1440x900).
// Exit code: 0 done, 1 failure (message on stderr).
import fs from "node:fs";
import http from "node:http";
import path from "node:path";
import { createRequire } from "node:module";

const [webDir, chromium, nodeModules, answersPath, outDir, participant, reloadAfterText] = process.argv.slice(2);
const reloadAfter = Number(reloadAfterText);
const require = createRequire(path.join(nodeModules, "noop.js"));
const puppeteer = require("puppeteer-core");
const answers = JSON.parse(fs.readFileSync(answersPath, "utf8"));
fs.mkdirSync(outDir, { recursive: true });

const types = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".json": "application/json", ".mp4": "video/mp4" };
const server = http.createServer((req, res) => {
  const url = new URL(req.url, "http://localhost");
  const file = path.join(path.resolve(webDir), decodeURIComponent(url.pathname));
  if (!file.startsWith(path.resolve(webDir)) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
    res.writeHead(404);
    res.end();
    return;
  }
  res.writeHead(200, { "Content-Type": types[path.extname(file)] || "application/octet-stream" });
  fs.createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
const base = `http://127.0.0.1:${server.address().port}/index.html?participant=${participant}`;

const browser = await puppeteer.launch({
  executablePath: chromium,
  headless: true,
  args: ["--no-sandbox", "--autoplay-policy=no-user-gesture-required", "--window-size=1920,1080"],
  defaultViewport: { width: 1440, height: 900 },
});
const sizes = [[1920, 1080], [1440, 900]];
const shots = new Set();
const fail = (message) => {
  throw new Error(message);
};

async function screenshot(page, kind) {
  if (shots.has(kind)) return;
  shots.add(kind);
  await page.screenshot({ path: path.join(outDir, `screen-${kind}.png`) });
}

const ANY_SCREEN =
  "#jspsych-fullscreen-btn, #jspsych-instructions-next, #jspsych-html-button-response-btngroup button, " +
  "#jspsych-survey-likert-form, #jspsych-html-keyboard-response-stimulus, #crowdlab-download";

/// The Likert screen at each window size: whether anything scrolls, the clip's box and the picture
/// in it (object-fit: contain), the statements' positions; one screenshot per size.
async function probeLikertLayout(page) {
  const layout = {};
  for (const [width, height] of sizes) {
    await page.setViewport({ width, height });
    await new Promise((r) => setTimeout(r, 400));
    layout[`${width}x${height}`] = await page.evaluate(() => {
      const rect = (el) => el.getBoundingClientRect();
      const v = document.querySelector("#crowdlab-study video");
      const box = rect(v);
      const scale = Math.min(box.width / v.videoWidth, box.height / v.videoHeight);
      return {
        viewport: [window.innerWidth, window.innerHeight],
        scroll: [document.scrollingElement.scrollWidth, document.scrollingElement.scrollHeight],
        video_box: [box.width, box.height],
        picture: [v.videoWidth * scale, v.videoHeight * scale],
        next_bottom: rect(document.querySelector("#jspsych-survey-likert-next")).bottom,
        statements: [...document.querySelectorAll(".jspsych-survey-likert-statement")].map((e) => [rect(e).left, rect(e).top]),
        scales: [...document.querySelectorAll(".jspsych-survey-likert-opts")].map((e) => [rect(e).left, rect(e).top, rect(e).width]),
      };
    });
    await page.screenshot({ path: path.join(outDir, `likert-${width}x${height}.png`) });
  }
  await page.setViewport({ width: 1440, height: 900 });
  fs.writeFileSync(path.join(outDir, "layout.json"), JSON.stringify(layout));
}

const jspsychCsv = (page) => page.evaluate(() => window.crowdlab.jsPsych.data.get().csv());

/// The trial number in the header of the current trial screen (0 when none).
async function currentTrial(page) {
  return page.evaluate(() => {
    const h = document.querySelector(".crowdlab-header");
    const m = h ? h.textContent.match(/rial (\d+) of/) : null;
    return m ? Number(m[1]) : 0;
  });
}

async function stimulusOf(page, trial) {
  return page.evaluate((t) => {
    const tl = window.crowdlabTimeline;
    const id = new URLSearchParams(location.search).get("participant");
    return tl.orders[window.crowdlab.orderParticipant(id, tl.order_ids)][t - 1].stimulus;
  }, trial);
}

async function waitGone(page, handle) {
  for (let i = 0; i < 400; i++) {
    if (!(await handle.evaluate((el) => el.isConnected))) return;
    await new Promise((r) => setTimeout(r, 25));
  }
  fail("a screen did not end after its answer");
}

/// Plays one screen; returns "done" at the end screen, "trial" after a trial's last screen.
async function step(page, answered) {
  const found = await page.waitForSelector(ANY_SCREEN, { timeout: 30000 });
  const id = await found.evaluate((el) => el.id || el.className);
  if (id === "crowdlab-download") return "done";
  if (id === "jspsych-fullscreen-btn") {
    await screenshot(page, "fullscreen");
    await found.click();
  } else if (id === "jspsych-instructions-next") {
    await screenshot(page, "instructions");
    await found.click();
  } else if (id === "jspsych-survey-likert-form") {
    const trial = await currentTrial(page);
    const stimulus = await stimulusOf(page, trial);
    await page.waitForFunction(() => {
      const v = document.querySelector("#crowdlab-study video");
      return !v || v.currentTime > 0.05;  // a looping clip plays above the questions
    }, { timeout: 10000 });
    if (!shots.has("trial-likert")) await probeLikertLayout(page);
    await screenshot(page, "trial-likert");
    const names = await page.$$eval("ul.jspsych-survey-likert-opts", (uls) => uls.map((u) => u.dataset.name));
    for (const q of names) await page.click(`ul[data-name="${q}"] input[value="${answers[stimulus][q] - 1}"]`);
    await page.click("#jspsych-survey-likert-next");
    await waitGone(page, found);
    answered.push(trial);
    return "trial";
  } else if (id.startsWith("jspsych-html-keyboard-response")) {
    const yesno = await page.$(".crowdlab-keys");
    if (yesno) {
      const trial = await currentTrial(page);
      const stimulus = await stimulusOf(page, trial);
      await screenshot(page, "trial-yesno");
      const q = Object.keys(answers[stimulus]).find((k) => answers[stimulus][k] === "yes" || answers[stimulus][k] === "no");
      await page.keyboard.press(answers[stimulus][q] === "yes" ? "y" : "n");
    } else {
      const title = await page.$eval(".crowdlab-text h2", (h) => h.textContent).catch(() => "text");
      await screenshot(page, "text-" + title.replace(/[^A-Za-z0-9]+/g, "_"));
      await page.keyboard.press("Space");
    }
  } else {
    await screenshot(page, "consent");
    await found.click();
  }
  await waitGone(page, found);
  return "screen";
}

let page = null;
try {
  page = await browser.newPage();
  page.on("pageerror", (e) => console.error("page error:", e.message));
  if (process.env.CROWDLAB_WEB_DEBUG) page.on("console", (m) => console.error("page console:", m.text()));
  await page.goto(base);
  const first = await page.waitForSelector("#jspsych-loading-progress-bar, #jspsych-fullscreen-btn", { timeout: 20000 });
  if ((await first.evaluate((el) => el.id)) === "jspsych-loading-progress-bar") await screenshot(page, "preload");
  const answered = [];
  const resume = {};
  for (let guard = 0; guard < 500; guard++) {
    const what = await step(page, answered);
    if (what === "done") break;
    if (what === "trial" && answered.length === reloadAfter && resume.before === undefined) {
      resume.before = answered.slice();
      fs.writeFileSync(path.join(outDir, "jspsych-1.csv"), await jspsychCsv(page));
      await page.reload();
      // Resumed: the first trial screen after the reload must be the next unanswered trial. Play the
      // screens before it (preload, full screen, instructions) without answering any trial.
      for (let g = 0; g < 50; g++) {
        await page.waitForSelector(ANY_SCREEN, { timeout: 30000 });
        if (await page.$("#jspsych-survey-likert-form, .crowdlab-keys, .crowdlab-header")) break;
        await step(page, answered);
      }
      resume.first_trial_after_reload = await currentTrial(page);
    }
  }
  await screenshot(page, "end");
  fs.writeFileSync(path.join(outDir, "jspsych-2.csv"), await jspsychCsv(page));
  const download = await page.$eval("#crowdlab-download", async (a) => (await fetch(a.href)).text());
  fs.writeFileSync(path.join(outDir, "download.json"), download);
  const storage = await page.evaluate(() => {
    const out = {};
    for (let i = 0; i < localStorage.length; i++) out[localStorage.key(i)] = JSON.parse(localStorage.getItem(localStorage.key(i)));
    return out;
  });
  fs.writeFileSync(path.join(outDir, "localstorage.json"), JSON.stringify(Object.values(storage)[0]));
  const fnv = await page.evaluate(() => ["", "a", "foobar", "P01", "5f2a0c9e1b"].map((s) => [s, window.crowdlab.fnv1a32(s)]));
  fs.writeFileSync(path.join(outDir, "fnv.json"), JSON.stringify(fnv));
  resume.answered = answered;
  fs.writeFileSync(path.join(outDir, "resume.json"), JSON.stringify(resume));
  await browser.close();
  server.close();
} catch (e) {
  console.error(`web participant: ${e.message}`);
  if (page) {
    await page.screenshot({ path: path.join(outDir, "failure.png") }).catch(() => {});
    const state = await page.evaluate(() => [document.body.innerHTML, JSON.stringify(localStorage)]).catch(() => []);
    fs.writeFileSync(path.join(outDir, "failure.txt"), state.join("\n\n"));
  }
  await browser.close();
  server.close();
  process.exit(1);
}
