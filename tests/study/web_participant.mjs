// A scripted participant for crowdlab's web study (export-web), in headless Chromium through the
// DevTools protocol (puppeteer-core, pointed at the system chromium). Used by tests/study/test_web_browser.cpp.
//
// node web_participant.mjs OPTIONS.json
//   OPTIONS: {web_dir, chromium, node_modules, answers (a JSON file {stimulus: {question: raw}}),
//   out_dir, participant, reload_after (0: no reload), layout_sizes ([[w, h], ...]: the first trial
//   screen is measured and photographed at each), early_input (try to answer before the lock opens and
//   during the inter-trial screen), decline (answer N at the consent), id_checks (open the page with ids
//   that import-web refuses, and with no id), jatos (web_dir holds a stub jatos.js that records its calls
//   in window.jatosStub: the study ends at "Saving your answers...", then waits for the stub's end call),
//   viewport ([w, h], default [1440, 900]), path_prefix (serve web_dir under this path, as JATOS serves a
//   study's assets under /publix/...)}.
// Serves web_dir on 127.0.0.1 (a tiny static server, no dependency), opens
// index.html?participant=PARTICIPANT (index.html alone when PARTICIPANT is empty), plays every screen
// (scale answers by number keys, yes/no by Y/N, Next by Enter), reloads once after reload_after answered trials, and writes to out_dir:
// download.json, localstorage.json, transcript.json (the page's transcript per page load), resume.json,
// jspsych-1.csv / jspsych-2.csv (jsPsych.data.get().csv() before the reload and at the end),
// layout.json with likert-WxH.png, early.json, ids.json, requests.json (the paths the page asked for),
// jatos.json (the stub's record, with jatos), end-layout.json and one screenshot per kind of screen.
// Exit code: 0 done, 1 failure (message on stderr).
import fs from "node:fs";
import http from "node:http";
import path from "node:path";
import { createRequire } from "node:module";

const options = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
const { web_dir: webDir, chromium, node_modules: nodeModules, out_dir: outDir, participant } = options;
const reloadAfter = options.reload_after || 0;
const viewport = options.viewport || [1440, 900];
const require = createRequire(path.join(nodeModules, "noop.js"));
const puppeteer = require("puppeteer-core");
const answers = JSON.parse(fs.readFileSync(options.answers, "utf8"));
fs.mkdirSync(outDir, { recursive: true });

const types = { ".html": "text/html", ".js": "text/javascript", ".css": "text/css", ".json": "application/json", ".mp4": "video/mp4" };
const prefix = options.path_prefix || "/";
const requests = [];
const server = http.createServer((req, res) => {
  const url = new URL(req.url, "http://localhost");
  requests.push(url.pathname);
  const file = path.join(path.resolve(webDir), decodeURIComponent(url.pathname.slice(prefix.length - 1)));
  if (!url.pathname.startsWith(prefix) || !file.startsWith(path.resolve(webDir)) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
    res.writeHead(404);
    res.end();
    return;
  }
  res.writeHead(200, { "Content-Type": types[path.extname(file)] || "application/octet-stream" });
  fs.createReadStream(file).pipe(res);
});
await new Promise((resolve) => server.listen(0, "127.0.0.1", resolve));
const origin = `http://127.0.0.1:${server.address().port}${prefix}index.html`;

const browser = await puppeteer.launch({
  executablePath: chromium,
  headless: true,
  args: ["--no-sandbox", "--autoplay-policy=no-user-gesture-required", "--window-size=1920,1080"],
  defaultViewport: { width: viewport[0], height: viewport[1] },
});
const shots = new Set();
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const fail = (message) => {
  throw new Error(message);
};

async function screenshot(page, kind) {
  if (shots.has(kind)) return;
  shots.add(kind);
  await page.screenshot({ path: path.join(outDir, `screen-${kind}.png`) });
}

/// The ids import-web refuses must not start the study; a bare link shows an empty id field.
async function idChecks(page) {
  const out = {};
  for (const bad of ["_P07", "-P07", "P 07"]) {
    await page.goto(`${origin}?participant=${encodeURIComponent(bad)}`);
    const shown = await page.waitForSelector("#crowdlab-invalid-id, .crowdlab-trial, #jspsych-fullscreen-btn, #jspsych-loading-progress-bar", { timeout: 20000 });
    out[bad] = { refused: (await shown.evaluate((el) => el.id)) === "crowdlab-invalid-id", text: await shown.evaluate((el) => el.textContent) };
    await screenshot(page, "invalid-id");
  }
  await page.goto(origin);
  const input = await page.waitForSelector("#crowdlab-id", { timeout: 20000 });
  out.bare = { value: await input.evaluate((el) => el.value) };
  await screenshot(page, "ask-id");
  await input.type("_P07");
  await page.click("#crowdlab-id-form button");
  await sleep(200);
  out.bare.error = await page.$eval("#crowdlab-id-error", (el) => el.textContent);
  out.bare.url_after_bad = page.url();
  const emptyKeys = await page.evaluate(() => Object.keys(localStorage).length);
  out.bare.storage_keys = emptyKeys;
  await page.evaluate(() => localStorage.clear());
  fs.writeFileSync(path.join(outDir, "ids.json"), JSON.stringify(out));
}

/// The first trial screen at each window size: scrolling, the clip's box and the picture in it
/// (object-fit: contain), the Next button, the cells; one screenshot per size.
async function probeLayout(page) {
  const layout = {};
  for (const [width, height] of options.layout_sizes || []) {
    await page.setViewport({ width, height });
    await sleep(400);
    layout[`${width}x${height}`] = await page.evaluate(() => {
      const rect = (el) => el.getBoundingClientRect();
      const v = document.querySelector("#crowdlab-video");
      const box = rect(v);
      const scale = Math.min(box.width / v.videoWidth, box.height / v.videoHeight);
      return {
        viewport: [window.innerWidth, window.innerHeight],
        scroll: [document.scrollingElement.scrollWidth, document.scrollingElement.scrollHeight],
        video_box: [box.width, box.height],
        picture: [v.videoWidth * scale, v.videoHeight * scale],
        next_bottom: rect(document.querySelector("#crowdlab-next")).bottom,
        cells: [...document.querySelectorAll(".crowdlab-cell")].map((e) => [rect(e).left, rect(e).top, rect(e).bottom]),
        background: getComputedStyle(document.body).backgroundColor,
      };
    });
    await page.screenshot({ path: path.join(outDir, `likert-${width}x${height}.png`) });
  }
  await page.setViewport({ width: viewport[0], height: viewport[1] });
  fs.writeFileSync(path.join(outDir, "layout.json"), JSON.stringify(layout));
}

const jspsychCsv = (page) => page.evaluate(() => window.crowdlab.jsPsych.data.get().csv());
const selectedCount = (page) => page.$$eval(".crowdlab-selected", (els) => els.length);

async function waitGone(page, handle) {
  for (let i = 0; i < 400; i++) {
    if (!(await handle.evaluate((el) => el.isConnected))) return;
    await sleep(25);
  }
  fail("a screen did not end after its answer");
}

const ANY_SCREEN = "#jspsych-fullscreen-btn, .crowdlab-text .crowdlab-hint, .crowdlab-trial, #crowdlab-download, #crowdlab-saving, #crowdlab-id";
const END = "#crowdlab-download, #crowdlab-saving";
const early = { during_inter_trial: null, after_onset: null };

/// Plays one trial: waits for its onset, (optionally) tries to answer too early, waits for the lock to
/// open, answers with number keys and Y / N, moves on with Enter.
async function playTrial(page, root, answered) {
  const trial = Number(await root.evaluate((el) => el.dataset.trial));
  const stimulus = await root.evaluate((el) => el.dataset.stimulus);
  if (options.early_input && early.during_inter_trial === null) {
    // Keys typed on the inter-trial screen (straight through the trial change) must not answer.
    if (await root.evaluate((el) => el.classList.contains("crowdlab-inter-trial"))) {
      await screenshot(page, "inter-trial");
      await page.keyboard.press("3");
      early.during_inter_trial = { was_inter_trial: true };
    }
  }
  await page.waitForFunction((el) => !el.classList.contains("crowdlab-inter-trial"), { timeout: 20000 }, root);
  await page.waitForFunction(() => document.querySelector("#crowdlab-video").currentTime > 0.02, { timeout: 20000 });
  if (options.early_input && early.after_onset === null) {
    const locked = await root.evaluate((el) => el.classList.contains("crowdlab-locked"));
    await page.keyboard.press("2");
    await page.keyboard.press("y");
    await page.click('[data-q="0"][data-v="1"]').catch(() => {});
    await page.keyboard.press("Enter");
    early.after_onset = {
      locked,
      next_label: await page.$eval("#crowdlab-next", (b) => b.textContent),
      selected: await selectedCount(page),
      still_here: await root.evaluate((el) => el.isConnected),
    };
    await screenshot(page, "trial-locked");
    if (early.during_inter_trial) early.during_inter_trial.selected = early.after_onset.selected;
  }
  await page.waitForFunction((el) => !el.classList.contains("crowdlab-locked"), { timeout: 30000 }, root);
  if (options.layout_sizes && !shots.has("trial")) await probeLayout(page);
  await screenshot(page, "trial");
  const questions = await page.evaluate(() => window.crowdlabTimeline.questions);
  for (const q of questions) {
    const raw = answers[stimulus][q.id];
    if (q.kind === "yesno") await page.keyboard.press(raw === 1 ? "y" : "n");
    else if (raw <= 9) await page.keyboard.press(String(raw));
    else await page.click(`[data-q="${questions.indexOf(q)}"][data-v="${raw}"]`);
  }
  await screenshot(page, "trial-answered");
  await page.keyboard.press("Enter");
  await waitGone(page, root);
  answered.push(trial);
}

/// Plays one screen; returns "done" at the end page, "trial" after a trial.
async function step(page, answered) {
  const found = await page.waitForSelector(ANY_SCREEN, { timeout: 30000 });
  const kind = await found.evaluate((el) => (el.id ? el.id : el.className));
  if (kind === "crowdlab-download" || kind === "crowdlab-saving") return "done";
  if (kind === "crowdlab-id") fail("the page asked for a participant id");
  if (kind === "jspsych-fullscreen-btn") {
    await screenshot(page, "fullscreen");
    await found.click();
    await waitGone(page, found);
    return "screen";
  }
  if (kind.startsWith("crowdlab-trial")) {
    await playTrial(page, found, answered);
    return "trial";
  }
  const title = await page.$eval(".crowdlab-title", (h) => h.textContent);
  await screenshot(page, "text-" + title.replace(/[^A-Za-z0-9]+/g, "_"));
  await sleep(350);  // keys within 300 ms of a text screen are ignored, as natively
  if (title === "Consent") {
    await page.keyboard.press(options.decline ? "n" : "y");
    if (options.decline) {
      await page.waitForSelector(END, { timeout: 20000 });
      return "done";
    }
  } else {
    await page.keyboard.press("Space");
  }
  await waitGone(page, found);
  return "screen";
}

let page = null;
try {
  page = await browser.newPage();
  page.on("pageerror", (e) => console.error("page error:", e.message));
  if (process.env.CROWDLAB_WEB_DEBUG) page.on("console", (m) => console.error("page console:", m.text()));
  if (options.id_checks) await idChecks(page);
  await page.goto(participant ? `${origin}?participant=${encodeURIComponent(participant)}` : origin);
  const answered = [];
  const resume = {};
  const transcripts = [];
  for (let guard = 0; guard < 1000; guard++) {
    const what = await step(page, answered);
    if (what === "done") break;
    if (what === "trial" && answered.length === reloadAfter && resume.before === undefined) {
      resume.before = answered.slice();
      fs.writeFileSync(path.join(outDir, "jspsych-1.csv"), await jspsychCsv(page));
      transcripts.push(await page.evaluate(() => window.crowdlab.transcript));
      await page.reload();
      // Resumed: the first trial screen after the reload must be the next unanswered trial. Play the
      // screens before it (preload, full screen, instructions) without answering any trial.
      let first = null;
      for (let g = 0; g < 50 && !first; g++) {
        await page.waitForSelector(ANY_SCREEN, { timeout: 30000 });
        first = await page.$(".crowdlab-trial");
        if (!first) await step(page, answered);
      }
      resume.first_trial_after_reload = first ? Number(await first.evaluate((el) => el.dataset.trial)) : 0;
    }
  }
  await screenshot(page, "end");
  if (options.jatos) {
    // The page ends the study only after its last appendResultData has resolved (the stub is slow).
    await page.waitForFunction(() => window.jatosStub && window.jatosStub.ended, { timeout: 20000 });
    fs.writeFileSync(path.join(outDir, "jatos.json"), JSON.stringify(await page.evaluate(() => window.jatosStub)));
  }
  transcripts.push(await page.evaluate(() => window.crowdlab.transcript));
  fs.writeFileSync(path.join(outDir, "transcript.json"), JSON.stringify(transcripts));
  fs.writeFileSync(path.join(outDir, "end.json"), JSON.stringify(await page.evaluate(() => document.querySelector("#crowdlab-study").innerText)));
  // Where the end page's body starts, as a share of the window width (text screens: 0.15, as natively).
  const endBodyLeft = await page.$eval("#crowdlab-study .crowdlab-body", (el) => el.getBoundingClientRect().left / window.innerWidth);
  fs.writeFileSync(path.join(outDir, "end-layout.json"), JSON.stringify({ body_left: endBodyLeft }));
  if (!options.decline) fs.writeFileSync(path.join(outDir, "jspsych-2.csv"), await jspsychCsv(page));
  if (await page.$("#crowdlab-download")) {
    const download = await page.$eval("#crowdlab-download", async (a) => (await fetch(a.href)).text());
    fs.writeFileSync(path.join(outDir, "download.json"), download);
  }
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
  fs.writeFileSync(path.join(outDir, "early.json"), JSON.stringify(early));
  fs.writeFileSync(path.join(outDir, "requests.json"), JSON.stringify(requests));
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
