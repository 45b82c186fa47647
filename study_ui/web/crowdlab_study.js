// crowdlab web study: runs timeline.json (written by `crowdlab export-web`) with jsPsych 8.
//
// Protocol: the same screens, texts and trial order as the native session (study_ui/run_session.cpp):
// instructions, consent (first session only), practice intro, part intros, a break every
// break_every test trials, one trial per stimulus, the end screen. The order is not computed here:
// timeline.json embeds the orders that crowdlab computed in C++ (build_trial_list). A participant id
// that is not embedded runs the order of embedded id fnv1a32(id) mod n (see web_export.hpp).
//
// Data safety: every trial's record is written to localStorage when the trial ends (and appended to
// the JATOS result data when jatos.js is present), so a reload or crash resumes at the first
// unanswered trial, with nothing lost or duplicated (each record carries its trial number; a trial
// with a record is never shown again). Without JATOS the end screen offers the data as a download.
//
// Video timing (per trial): requestVideoFrameCallback where the browser has it
// (https://wicg.github.io/video-rvfc/): onset = expectedDisplayTime of the first presented frame,
// frames presented = span of metadata.presentedFrames; dropped frames from
// HTMLVideoElement.getVideoPlaybackQuality(); the display refresh rate from the median interval of
// requestAnimationFrame callbacks during the trial. Response times run from that onset.
/* global initJsPsych, jsPsychPreload, jsPsychFullscreen, jsPsychInstructions, jsPsychHtmlKeyboardResponse,
   jsPsychHtmlButtonResponse, jsPsychSurveyLikert, jsPsychVideoKeyboardResponse, jatos */
(function () {
  "use strict";

  const DATA_FORMAT = "crowdlab-web-data";
  const ID_PATTERN = /^[A-Za-z0-9_-]{1,64}$/;
  const hasJatos = () => typeof jatos !== "undefined";

  function fnv1a32(text) {
    let h = 0x811c9dc5;
    for (const byte of new TextEncoder().encode(text)) {
      h ^= byte;
      h = Math.imul(h, 0x01000193) >>> 0;
    }
    return h >>> 0;
  }

  function orderParticipant(id, embedded) {
    return embedded.includes(id) ? id : embedded[fnv1a32(id) % embedded.length];
  }

  function escapeHtml(text) {
    return String(text).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
  }

  function textPage(title, body) {
    const paragraphs = escapeHtml(body).split("\n").join("<br>");
    return `<div class="crowdlab-text"><h2>${escapeHtml(title)}</h2><p>${paragraphs}</p></div>`;
  }

  /// localStorage record of one participant's answers, keyed by study (spec hash) and participant.
  class AnswerStore {
    constructor(study, participant, orderOf) {
      this.key = `crowdlab:${study.spec_hash}:${participant}`;
      const saved = this.read();
      this.data = saved || {
        format: DATA_FORMAT,
        format_version: 1,
        study: study.name,
        spec_hash: study.spec_hash,
        manifest_sha256: study.manifest_sha256,
        participant,
        order_of: orderOf,
        sessions: [],
        complete: false,
        records: [],
      };
      this.pending = Promise.resolve();
    }
    read() {
      try {
        const text = window.localStorage.getItem(this.key);
        return text ? JSON.parse(text) : null;
      } catch (e) {
        return null;
      }
    }
    write() {
      try {
        window.localStorage.setItem(this.key, JSON.stringify(this.data));
      } catch (e) {
        console.error("crowdlab: localStorage write failed", e);
      }
    }
    doneTrials() {
      return new Set(this.data.records.map((r) => r.trial));
    }
    startSession(info) {
      this.data.sessions.push(info);
      this.write();
      return this.data.sessions.length;
    }
    add(record) {
      if (this.doneTrials().has(record.trial)) return false;
      this.data.records.push(record);
      this.write();
      // One request at a time, in trial order; the study ends only after the last one (finish()).
      if (hasJatos() && jatos.appendResultData)
        this.pending = this.pending
          .catch((e) => console.error("crowdlab: JATOS appendResultData failed (localStorage keeps the data)", e))
          .then(() => jatos.appendResultData(JSON.stringify(record) + "\n"));
      return true;
    }
  }

  /// Presentation timing of the clip(s) of one trial, over all of its screens.
  class VideoTiming {
    constructor() {
      this.onset = null;
      this.onsetUtc = null;
      this.framesPresented = 0;
      this.framesDropped = 0;
      this.rafIntervals = [];
      this.usedRvfc = false;
      this.video = null;
    }
    attach(video) {
      if (!video) return;
      this.video = video;
      const span = { first: null, last: null };
      this.span = span;
      if ("requestVideoFrameCallback" in HTMLVideoElement.prototype) {
        this.usedRvfc = true;
        const onFrame = (now, meta) => {
          if (this.video !== video) return;
          if (this.onset === null) {
            this.onset = meta.expectedDisplayTime || now;
            this.onsetUtc = new Date(performance.timeOrigin + this.onset).toISOString();
          }
          if (span.first === null) span.first = meta.presentedFrames;
          span.last = meta.presentedFrames;
          video.requestVideoFrameCallback(onFrame);
        };
        video.requestVideoFrameCallback(onFrame);
      } else {
        video.addEventListener("playing", () => {
          if (this.onset === null) {
            this.onset = performance.now();
            this.onsetUtc = new Date().toISOString();
          }
        }, { once: true });
      }
      let previous = null;
      const onAnimationFrame = (t) => {
        if (this.video !== video) return;
        if (previous !== null) this.rafIntervals.push(t - previous);
        previous = t;
        requestAnimationFrame(onAnimationFrame);
      };
      requestAnimationFrame(onAnimationFrame);
    }
    detach() {
      const video = this.video;
      if (!video) return;
      if (this.span && this.span.first !== null) this.framesPresented += this.span.last - this.span.first + 1;
      if (video.getVideoPlaybackQuality) this.framesDropped += video.getVideoPlaybackQuality().droppedVideoFrames;
      this.video = null;
    }
    summary() {
      const sorted = this.rafIntervals.slice().sort((a, b) => a - b);
      const median = sorted.length ? sorted[Math.floor(sorted.length / 2)] : 0;
      return {
        onset_utc: this.onsetUtc,
        frames_presented: this.framesPresented,
        frames_dropped: this.framesDropped,
        refresh_hz: median > 0 ? Math.round((1000 / median) * 10) / 10 : null,
        timing_api: this.usedRvfc ? "requestVideoFrameCallback" : "playing-event",
      };
    }
  }

  function participantId(params) {
    let id = params.get("participant") || params.get("PROLIFIC_PID") || "";
    if (!id && hasJatos()) {
      const q = jatos.urlQueryParameters || {};
      id = q.participant || q.PROLIFIC_PID || (jatos.workerId ? `jatos${jatos.workerId}` : "");
    }
    return id;
  }

  function showMessage(html) {
    document.getElementById("crowdlab-study").innerHTML = `<div class="crowdlab-text">${html}</div>`;
  }

  /// Pilot helper: no id in the URL and no JATOS: ask for one (an experimenter trying the study).
  function askForId(timeline) {
    const example = timeline.order_ids[0];
    showMessage(
      "<h2>Participant id</h2><p>This link has no <code>?participant=</code> (or <code>PROLIFIC_PID</code>).</p>" +
        `<form id="crowdlab-id-form"><input id="crowdlab-id" value="${escapeHtml(example)}" pattern="[A-Za-z0-9_-]{1,64}" required>` +
        ' <button class="jspsych-btn" type="submit">Start</button></form>',
    );
    document.getElementById("crowdlab-id-form").addEventListener("submit", (event) => {
      event.preventDefault();
      const url = new URL(window.location.href);
      url.searchParams.set("participant", document.getElementById("crowdlab-id").value);
      window.location.href = url.toString();
    });
  }

  function likertLabels(q) {
    if (q.point_labels && q.point_labels.length === q.points) return q.point_labels.map((l, i) => `${i + 1}<br>${escapeHtml(l)}`);
    const labels = [];
    for (let i = 1; i <= q.points; i++) {
      let label = String(i);
      if (i === 1 && q.low_label) label += `<br>${escapeHtml(q.low_label)}`;
      if (i === q.points && q.high_label) label += `<br>${escapeHtml(q.high_label)}`;
      labels.push(label);
    }
    return labels;
  }

  function run(timeline, participant) {
    const study = timeline.study;
    const screens = timeline.screens;
    const questions = timeline.questions;
    const orderOf = orderParticipant(participant, timeline.order_ids);
    const order = timeline.orders[orderOf];
    const store = new AnswerStore(study, participant, orderOf);
    const done = store.doneTrials();
    const session = store.startSession({
      start_utc: new Date().toISOString(),
      resumed_at_trials_done: done.size,
      screen: { width: window.screen.width, height: window.screen.height, device_pixel_ratio: window.devicePixelRatio },
      user_agent: navigator.userAgent,
      jatos: hasJatos(),
    });
    document.getElementById("crowdlab-study").innerHTML = "";
    const jsPsych = initJsPsych({
      display_element: "crowdlab-study",
      on_finish: () => finish(jsPsych, store, study, screens),
    });
    window.crowdlab.jsPsych = jsPsych;  // for jsPsych.data.get().csv() / .json() (pilots, the browser test)
    const clipUrl = (stimulusId) => timeline.stimuli[stimulusId].file;
    const videoHtml = (src, loop) => {
      const url = jsPsych.pluginAPI.getVideoBuffer(src) || src;
      return `<video class="crowdlab-video" src="${url}" autoplay muted playsinline${loop ? " loop" : ""}></video>`;
    };
    const keyScreen = (title, body) => ({
      type: jsPsychHtmlKeyboardResponse,
      stimulus: textPage(title, body),
      choices: "ALL_KEYS",
      data: { crowdlab_screen: title },
    });

    const remaining = order.filter((t) => !done.has(t.trial));
    const tl = [];
    if (remaining.length === 0) {
      tl.push(keyScreen(screens.finished_title, screens.finished));
      jsPsych.run(tl);
      return;
    }
    tl.push({
      type: jsPsychPreload,
      video: [...new Set(remaining.map((t) => clipUrl(t.stimulus)))],
      show_progress_bar: true,
      message: "<p>Loading the videos...</p>",
      continue_after_error: false,
      error_message: "<p>The videos could not be loaded. Please check your connection and reload this page.</p>",
    });
    tl.push({
      type: jsPsychFullscreen,
      fullscreen_mode: true,
      message: "<p>The study runs in full screen. Please keep this window in full screen until the end.</p>",
      button_label: "Continue",
    });
    if (screens.instructions)
      tl.push({ type: jsPsychInstructions, pages: [textPage("Instructions", screens.instructions)], show_clickable_nav: true, button_label_next: "Continue", allow_backward: false });
    if (screens.consent && done.size === 0)
      tl.push({
        type: jsPsychHtmlButtonResponse,
        stimulus: textPage("Consent", screens.consent),
        choices: ["I agree", "I do not agree"],
        on_finish: (data) => {
          if (data.response !== 0) jsPsych.abortExperiment(textPage("Thank you", "You did not agree, so the study ends here. You may close this window."));
        },
      });

    const multipleBlocks = order.some((t) => !t.practice && t.block_number > 1);
    let testDone = order.filter((t) => !t.practice && done.has(t.trial)).length;
    let inPractice = false;
    let currentBlock = "";
    for (const t of order) {
      if (done.has(t.trial)) continue;
      if (t.practice && !inPractice) tl.push(keyScreen(screens.practice_title, screens.practice_intro));
      if (!t.practice && (inPractice || t.block !== currentBlock) && (multipleBlocks || inPractice)) {
        const title = multipleBlocks ? screens.part_title_prefix + t.block_number : screens.main_part_title;
        tl.push(keyScreen(title, inPractice ? screens.after_practice : screens.block_intro));
      }
      inPractice = t.practice;
      currentBlock = t.block;
      tl.push(...trialScreens(t));
      if (!t.practice) ++testDone;
      const last = t.trial === order.length;
      if (!last && !t.practice && study.break_every > 0 && testDone % study.break_every === 0)
        tl.push(keyScreen(screens.break_title, screens.break_text));
    }
    tl.push(keyScreen(screens.finished_title, screens.finished));
    jsPsych.run(tl);

    /// The screens of one trial: the clip (played once, when loop_video is false), then one screen per
    /// yes/no question (keys Y / N) and one page per run of scale questions, in question order. With
    /// loop_video the clip loops on every question screen, as on the native trial screen.
    function trialScreens(t) {
      const src = clipUrl(t.stimulus);
      const timing = new VideoTiming();
      const answers = [];
      const header = t.practice ? `Practice: trial ${t.trial} of ${order.length}` : `Trial ${t.trial} of ${order.length}`;
      const headerHtml = `<div class="crowdlab-header">${escapeHtml(header)}</div>`;
      const media = study.loop_video ? videoHtml(src, true) : "";
      const sinceOnset = (screenStart) => {
        const now = performance.now();
        const from = timing.onset !== null ? timing.onset : screenStart;
        return Math.max(0, Math.round((now - from) * 10) / 10);
      };
      const out = [];
      let screenStart = 0;
      const onLoad = () => {
        screenStart = performance.now();
        timing.attach(document.querySelector("#crowdlab-study video"));
      };
      if (!study.loop_video)
        out.push({
          type: jsPsychVideoKeyboardResponse,
          stimulus: [src],
          prompt: headerHtml,
          choices: "NO_KEYS",
          trial_ends_after_video: true,
          autoplay: true,
          controls: false,
          on_load: onLoad,
          on_finish: () => timing.detach(),
          data: { crowdlab_trial: t.trial, crowdlab_part: "video" },
        });
      for (let i = 0; i < questions.length; ) {
        const q = questions[i];
        if (q.kind === "yesno") {
          out.push({
            type: jsPsychHtmlKeyboardResponse,
            css_classes: media ? ["crowdlab-video-page"] : [],
            stimulus: `${headerHtml}${media}<p class="crowdlab-question">${escapeHtml(q.text)}</p>` +
              `<p class="crowdlab-keys">Press <kbd>Y</kbd> for ${escapeHtml(q.high_label || "yes")}, <kbd>N</kbd> for ${escapeHtml(q.low_label || "no")}.</p>`,
            choices: ["y", "n"],
            on_load: onLoad,
            on_finish: (data) => {
              answers.push({ question: q.id, response: data.response === "y" ? 1 : 0, rt_ms: sinceOnset(screenStart), timestamp: new Date().toISOString() });
              timing.detach();
            },
            data: { crowdlab_trial: t.trial, crowdlab_part: q.id },
          });
          ++i;
          continue;
        }
        const page = [];
        while (i < questions.length && questions[i].kind !== "yesno") page.push(questions[i++]);
        // Layout (crowdlab_study.css): the statements in a grid of up to three columns, each scale as
        // wide as its column (scale_width null), and, with the looping clip, the page filling the
        // window: the clip gets the height the statements leave, so nothing scrolls.
        const columns = page.length >= 5 ? 3 : page.length >= 2 ? 2 : 1;
        out.push({
          type: jsPsychSurveyLikert,
          css_classes: [`crowdlab-scale-columns-${columns}`].concat(media ? ["crowdlab-video-page"] : []),
          preamble: `${headerHtml}${media}`,
          questions: page.map((pq) => ({ prompt: escapeHtml(pq.text), labels: likertLabels(pq), required: true, name: pq.id })),
          button_label: "Next",
          scale_width: columns > 1 ? null : 720,
          on_load: onLoad,
          on_finish: (data) => {
            const rt = sinceOnset(screenStart);
            const stamp = new Date().toISOString();
            for (const pq of page) answers.push({ question: pq.id, response: data.response[pq.id] + 1, rt_ms: rt, timestamp: stamp });
            timing.detach();
          },
          data: { crowdlab_trial: t.trial, crowdlab_part: page.map((pq) => pq.id).join(",") },
        });
      }
      // The record is saved when the trial's last screen ends.
      const lastScreen = out[out.length - 1];
      const answerFinish = lastScreen.on_finish;
      lastScreen.on_finish = (data) => {
        answerFinish(data);
        const record = {
          format: DATA_FORMAT,
          participant,
          order_of: orderOf,
          session,
          spec_hash: study.spec_hash,
          trial: t.trial,
          stimulus: t.stimulus,
          stimulus_sha256: timeline.stimuli[t.stimulus].sha256,
          block: t.block,
          practice: t.practice,
          answers,
          video: timing.summary(),
        };
        store.add(record);
        data.crowdlab_record = record;
      };
      return out;
    }
  }

  function finish(jsPsych, store, study, screens) {
    const complete = store.data.records.length === window.crowdlabTimeline.orders[store.data.order_of].length;
    store.data.complete = complete;
    store.data.sessions[store.data.sessions.length - 1].end_utc = new Date().toISOString();
    store.write();
    if (!complete) return;  // consent declined: abortExperiment already showed its message
    if (hasJatos()) {
      store.pending.catch(() => {}).then(() => {
        if (study.completion_url) jatos.endStudyAndRedirect(study.completion_url);
        else jatos.endStudy();
      });
      return;
    }
    const file = new Blob([JSON.stringify(store.data, null, 1)], { type: "application/json" });
    const name = `${study.name}_${store.data.participant}.json`;
    const link = study.completion_url
      ? `<p><a class="jspsych-btn" id="crowdlab-complete" href="${escapeHtml(study.completion_url)}">Finish and return to the panel</a></p>`
      : "";
    showMessage(
      `<h2>${escapeHtml(screens.finished_title)}</h2><p>The session is complete. Thank you for taking part!</p>` +
        `<p><a class="jspsych-btn" id="crowdlab-download" download="${escapeHtml(name)}" href="${URL.createObjectURL(file)}">Download the data (${escapeHtml(name)})</a></p>` +
        link,
    );
  }

  function start() {
    fetch("timeline.json")
      .then((response) => {
        if (!response.ok) throw new Error(`timeline.json: HTTP ${response.status}`);
        return response.json();
      })
      .then((timeline) => {
        window.crowdlabTimeline = timeline;
        const id = participantId(new URLSearchParams(window.location.search));
        if (!id) return askForId(timeline);
        if (!ID_PATTERN.test(id)) return showMessage(`<h2>Invalid participant id</h2><p>'${escapeHtml(id)}' must be 1-64 characters of A-Z a-z 0-9 _ -.</p>`);
        run(timeline, id);
      })
      .catch((error) => showMessage(`<h2>The study could not start</h2><p>${escapeHtml(error.message)}</p><p>Open it through a web server (see docs/online.md), not as a file.</p>`));
  }

  window.crowdlab = { fnv1a32, orderParticipant };
  if (hasJatos()) jatos.onLoad(start);
  else start();
})();
