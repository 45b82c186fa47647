// crowdlab web study: interprets the session plan in timeline.json (written by `crowdlab export-web`)
// with jsPsych 8.
//
// Protocol: nothing is decided here. timeline.json holds, per embedded participant id, the plan that
// crowdlab computed in C++ (study_ui/session_plan.hpp) and that the native window interprets too: the
// screens with their titles, texts and hint lines, the trials with their headers and minimum viewing
// times, in order; the inter-trial screen; the participant id rule. A participant id that is not
// embedded runs the plan of embedded id fnv1a32(id) mod n (see web_export.hpp). What only a browser
// does (loading the clips first, asking for full screen, the end page's download) is in docs/online.md.
//
// Trial screen (as the native one, trial_screen.hpp): the header, the clip as large as the questions
// leave, the questions in a grid of up to three columns (filled column by column on two rows, so seed
// 000's item pairs share a column) and the Next button at the grid's right. Answers: a click on a scale
// point or a Yes/No button, number keys for the first unanswered scale question (10 and 11 as two
// digits), Y / N for the yes/no question, Enter or Space for Next. Before the minimum viewing time has
// passed since the onset (and before a play-once clip has ended) the answers are locked: nothing is
// accepted and Next reads "Watch the clip". Keys and clicks before the onset never reach a trial.
//
// Data safety: every trial's record is written to localStorage when the trial ends (and appended to
// the JATOS result data when jatos.js is present), so a reload or crash resumes at the first
// unanswered trial, with nothing lost or duplicated. The consent decision is a record of its own.
//
// Video timing (per trial): requestVideoFrameCallback (https://wicg.github.io/video-rvfc/): onset =
// expectedDisplayTime of the first presented frame; every presented frame's display time is kept
// (frame_times_ms, from the onset) so that import-web computes the native frame-interval columns;
// frames presented = span of metadata.presentedFrames; dropped frames from getVideoPlaybackQuality();
// the display refresh rate from the median requestAnimationFrame interval. Response times run from the
// onset.
/* global initJsPsych, jsPsychModule, jsPsychPreload, jsPsychFullscreen, jatos */
(function () {
  "use strict";

  const DATA_FORMAT = "crowdlab-web-data";
  const DEBOUNCE_MS = 300;  // keys on a text screen this soon after it appeared are ignored (native too)
  const hasJatos = () => typeof jatos !== "undefined";
  /// What the page showed, in order: the web side of the lab/online parity test (ScriptedPresenter's
  /// transcript is the native side).
  const transcript = [];

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

  function element(tag, className, text) {
    const el = document.createElement(tag);
    if (className) el.className = className;
    if (text !== undefined) el.textContent = text;
    return el;
  }

  /// A text screen as the native one draws it: title, body (line breaks kept), hint line at the bottom.
  function textPage(title, text, hint) {
    const page = element("div", "crowdlab-text");
    page.append(element("h2", "crowdlab-title", title), element("p", "crowdlab-body", text));
    if (hint) page.append(element("p", "crowdlab-hint", hint));
    return page;
  }

  /// localStorage record of one participant's answers, keyed by study (spec hash) and participant.
  class AnswerStore {
    constructor(study, participant, orderOf) {
      this.key = `crowdlab:${study.spec_hash}:${participant}`;
      const saved = this.read();
      this.data = saved || {
        format: DATA_FORMAT,
        format_version: 2,
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
    /// JATOS: one request at a time, in order; the study ends only after the last one (finish()).
    submit(record) {
      if (hasJatos() && jatos.appendResultData)
        this.pending = this.pending
          .catch((e) => console.error("crowdlab: JATOS appendResultData failed (localStorage keeps the data)", e))
          .then(() => jatos.appendResultData(JSON.stringify(record) + "\n"));
    }
    add(record) {
      if (this.doneTrials().has(record.trial)) return false;
      this.data.records.push(record);
      this.write();
      this.submit(record);
      return true;
    }
    setConsent(record) {
      this.data.consent_record = record;
      this.write();
      this.submit(record);
    }
  }

  /// Presentation timing of one trial's clip.
  class VideoTiming {
    constructor() {
      this.onset = null;
      this.onsetUtc = null;
      this.frameTimes = [];
      this.span = { first: null, last: null };
      this.rafIntervals = [];
      this.usedRvfc = "requestVideoFrameCallback" in HTMLVideoElement.prototype;
      this.video = null;
      this.onOnset = () => {};
    }
    setOnset(t) {
      if (this.onset !== null) return;
      this.onset = t;
      this.onsetUtc = new Date(performance.timeOrigin + t).toISOString();
      this.onOnset();
    }
    attach(video) {
      this.video = video;
      if (this.usedRvfc) {
        const onFrame = (now, meta) => {
          if (this.video !== video) return;
          const shown = meta.expectedDisplayTime || now;
          this.setOnset(shown);
          this.frameTimes.push(Math.round((shown - this.onset) * 10) / 10);
          if (this.span.first === null) this.span.first = meta.presentedFrames;
          this.span.last = meta.presentedFrames;
          video.requestVideoFrameCallback(onFrame);
        };
        video.requestVideoFrameCallback(onFrame);
      } else {
        video.addEventListener("playing", () => this.setOnset(performance.now()), { once: true });
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
      this.framesDropped = video.getVideoPlaybackQuality ? video.getVideoPlaybackQuality().droppedVideoFrames : 0;
      this.video = null;
    }
    summary(interTrialMs) {
      const sorted = this.rafIntervals.slice().sort((a, b) => a - b);
      const median = sorted.length ? sorted[Math.floor(sorted.length / 2)] : 0;
      return {
        onset_utc: this.onsetUtc,
        inter_trial_ms: interTrialMs,
        frames_presented: this.span.first === null ? 0 : this.span.last - this.span.first + 1,
        frames_dropped: this.framesDropped || 0,
        frame_times_ms: this.frameTimes,
        refresh_hz: median > 0 ? Math.round((1000 / median) * 10) / 10 : null,
        timing_api: this.usedRvfc ? "requestVideoFrameCallback" : "playing-event",
      };
    }
  }

  /// A jsPsych plugin that hands the display to a function: every screen of the plan is drawn here, so
  /// the page needs no jsPsych plugin whose behaviour would differ from the native window's.
  class CrowdlabScreenPlugin {
    constructor(jsPsych) {
      this.jsPsych = jsPsych;
    }
    trial(displayElement, trial) {
      trial.run(displayElement, (data) => this.jsPsych.finishTrial(data));
    }
  }
  CrowdlabScreenPlugin.info = {
    name: "crowdlab-screen",
    version: "2",
    parameters: { run: { type: jsPsychModule.ParameterType.FUNCTION, default: undefined } },
    data: {},
  };

  /// Listens to keys (and clicks) on the document until `stop()`: key repeats never count.
  function listen(onKey, onClick) {
    const key = (e) => {
      if (e.repeat) return;
      onKey(e);
    };
    document.addEventListener("keydown", key);
    if (onClick) document.addEventListener("click", onClick);
    return () => {
      document.removeEventListener("keydown", key);
      if (onClick) document.removeEventListener("click", onClick);
    };
  }

  function participantId(params) {
    let id = params.get("participant") || params.get("PROLIFIC_PID") || "";
    if (!id && hasJatos()) {
      const q = jatos.urlQueryParameters || {};
      id = q.participant || q.PROLIFIC_PID || (jatos.workerId ? `jatos${jatos.workerId}` : "");
    }
    return id;
  }

  /// A text screen as the participant sees it (read back from the page), for the transcript.
  function shownScreen(kind, page) {
    const hint = page.querySelector(".crowdlab-hint");
    return {
      screen: kind,
      title: page.querySelector(".crowdlab-title").textContent,
      text: page.querySelector(".crowdlab-body").textContent,
      hint: hint ? hint.textContent : null,
    };
  }

  function showMessage(title, text) {
    const root = document.getElementById("crowdlab-study");
    root.replaceChildren(textPage(title, text));
    return root.firstChild;
  }

  /// No id in the link and no JATOS: an empty field, checked with the study's id rule (a pilot, or an
  /// experimenter starting a participant). It is never pre-filled: several people following a bare link
  /// must not all become the same participant.
  function askForId(timeline) {
    const page = showMessage("Participant id", "This link has no participant id. Type the id you were given.");
    const form = element("form");
    form.id = "crowdlab-id-form";
    const input = element("input");
    input.id = "crowdlab-id";
    input.value = "";
    input.autocomplete = "off";
    const error = element("p", "crowdlab-error");
    error.id = "crowdlab-id-error";
    const button = element("button", "jspsych-btn", "Start");
    button.type = "submit";
    form.append(input, " ", button, error);
    page.append(form);
    input.focus();
    form.addEventListener("submit", (event) => {
      event.preventDefault();
      const id = input.value.trim();
      if (!validId(timeline, id)) {
        error.textContent = idMessage(timeline, id);
        return;
      }
      const url = new URL(window.location.href);
      url.searchParams.set("participant", id);
      window.location.href = url.toString();
    });
  }

  const validId = (timeline, id) => new RegExp(timeline.participant_id.pattern).test(id);
  const idMessage = (timeline, id) => `The participant id '${id}' ${timeline.participant_id.rule}.`;

  function run(timeline, participant) {
    const study = timeline.study;
    const questions = timeline.questions;
    const orderOf = orderParticipant(participant, timeline.order_ids);
    const plan = timeline.plans[orderOf];
    const store = new AnswerStore(study, participant, orderOf);
    const done = store.doneTrials();
    const consentRecord = store.data.consent_record;
    const session = store.startSession({
      start_utc: new Date().toISOString(),
      resumed_at_trials_done: done.size,
      screen: { width: window.screen.width, height: window.screen.height, device_pixel_ratio: window.devicePixelRatio },
      user_agent: navigator.userAgent,
      jatos: hasJatos(),
    });
    document.getElementById("crowdlab-study").replaceChildren();
    const jsPsych = initJsPsych({
      display_element: "crowdlab-study",
      on_finish: () => finish(jsPsych, store, study, plan),
    });
    window.crowdlab.jsPsych = jsPsych;  // for jsPsych.data.get().csv() / .json() (pilots, the browser test)
    const clipUrl = (stimulusId) => timeline.stimuli[stimulusId].file;
    const recordBase = () => ({ format: DATA_FORMAT, participant, order_of: orderOf, session, spec_hash: study.spec_hash });

    // The resume rule of session_plan.hpp (skip_on_resume), exactly.
    const skipOnResume = (step) => (step.first_session_only && done.size > 0) || (step.skip_if_done > 0 && done.has(step.skip_if_done));
    const steps = plan.filter((step) => !skipOnResume(step));
    if (consentRecord && !consentRecord.consent.given) {
      declinedPage(store);
      return;
    }
    const tl = [];
    const remaining = steps.filter((s) => s.kind === "trial");
    if (remaining.length > 0) {
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
    }
    for (const step of steps) {
      if (step.kind === "trial") tl.push(trialScreen(step));
      else if (step.screen === "finished") break;  // finish() shows it, after the data are safe
      else tl.push(textScreen(step));
    }
    jsPsych.run(tl);

    function textScreen(step) {
      const consent = step.screen === "consent";
      return {
        type: CrowdlabScreenPlugin,
        data: { crowdlab_screen: step.screen },
        run: (display, end) => {
          const page = textPage(step.title, step.text, step.hint);
          display.replaceChildren(page);
          transcript.push(shownScreen(step.screen, page));
          const shown = performance.now();
          const ready = () => performance.now() - shown > DEBOUNCE_MS;
          const stop = listen(
            (e) => {
              if (!ready()) return;
              const key = e.key.toLowerCase();
              if (!consent) return finishWith({ response: key });
              if (key !== "y" && key !== "n") return;
              const record = Object.assign(recordBase(), {
                kind: "consent",
                consent: { given: key === "y", utc: new Date().toISOString(), session },
              });
              store.setConsent(record);
              if (key === "y") return finishWith({ response: key, crowdlab_record: record });
              stop();  // declined: the session ends here (finish() shows the page and delivers the record)
              jsPsych.abortExperiment("", { response: key, crowdlab_record: record });
            },
            consent ? null : () => ready() && finishWith({ response: "click" }),
          );
          function finishWith(data) {
            stop();
            end(data);
          }
        },
      };
    }

    /// One trial: the inter-trial screen while the clip gets ready (at least inter_trial.min_ms), then
    /// the clip and the questions, locked until the minimum viewing time has passed.
    function trialScreen(step) {
      return {
        type: CrowdlabScreenPlugin,
        data: { crowdlab_trial: step.trial },
        run: (display, end) => {
          const timing = new VideoTiming();
          const answers = new Array(questions.length).fill(null);
          const view = trialView(display, step);
          const interStart = performance.now();
          let unlocked = false;
          let videoEnded = study.loop_video;
          let digit = null;  // an open first digit on a 10- or 11-point scale
          view.showInterTrial(timeline.inter_trial.screen === "fixation");
          transcript.push({ inter_trial: timeline.inter_trial.screen });
          const video = view.video;
          video.src = jsPsych.pluginAPI.getVideoBuffer(clipUrl(step.stimulus)) || clipUrl(step.stimulus);
          video.loop = study.loop_video;
          video.muted = true;
          video.playsInline = true;
          video.addEventListener("ended", () => {
            videoEnded = true;
            updateLock();
          });
          const ready = new Promise((resolve) => {
            if (video.readyState >= 3) resolve();
            else video.addEventListener("canplay", resolve, { once: true });
          });
          const minimum = new Promise((resolve) => setTimeout(resolve, timeline.inter_trial.min_ms));
          let interTrialMs = null;
          timing.onOnset = () => {
            interTrialMs = Math.round((timing.onset - interStart) * 10) / 10;
            transcript.push({ trial: step.trial, header: view.header.textContent });
          };
          Promise.all([ready, minimum]).then(() => {
            view.showTrial();
            timing.attach(video);
            video.play().catch((e) => console.error("crowdlab: play failed", e));
          });
          const lockTimer = setInterval(updateLock, 20);
          function updateLock() {
            if (unlocked || timing.onset === null || !videoEnded) return;
            if (performance.now() - timing.onset < step.min_view_ms) return;
            unlocked = true;
            digit = null;
            clearInterval(lockTimer);
            view.setLocked(false, answers);
          }
          const sinceOnset = () => Math.max(0, Math.round((performance.now() - timing.onset) * 10) / 10);
          function answer(q, value) {
            if (!unlocked) return;
            answers[q] = { question: questions[q].id, response: value, rt_ms: sinceOnset(), timestamp: new Date().toISOString() };
            view.showAnswers(answers);
          }
          function next() {
            if (!unlocked || answers.some((a) => a === null)) return;
            stop();
            clearInterval(lockTimer);
            timing.detach();
            video.pause();
            const record = Object.assign(recordBase(), {
              trial: step.trial,
              stimulus: step.stimulus,
              stimulus_sha256: timeline.stimuli[step.stimulus].sha256,
              block: step.block,
              practice: step.practice,
              answers,
              video: timing.summary(interTrialMs),
            });
            store.add(record);
            end({ crowdlab_record: record });
          }
          const firstUnanswered = (kind) => questions.findIndex((q, i) => q.kind === kind && answers[i] === null);
          const stop = listen(
            (e) => {
              // A focused button would also turn Enter or Space into a click: the key alone counts.
              if (e.key === "Enter" || e.key === " ") e.preventDefault();
              if (!unlocked) return;  // before onset + min_view_ms: dropped, as natively
              const key = e.key;
              if (/^[0-9]$/.test(key)) {
                enterDigit(Number(key));
                return;
              }
              digit = null;
              const yn = firstUnanswered("yesno");
              if (yn >= 0 && (key === "y" || key === "Y")) answer(yn, 1);
              else if (yn >= 0 && (key === "n" || key === "N")) answer(yn, 0);
              else if (key === "Enter" || key === " ") next();
            },
            (e) => {
              const target = e.target.closest("[data-q], #crowdlab-next");
              if (!target || !unlocked) return;
              digit = null;
              if (target.id === "crowdlab-next") next();
              else answer(Number(target.dataset.q), Number(target.dataset.v));
            },
          );
          /// Number keys, exactly as natively (scale_keys.cpp): 1..9 answer the first unanswered scale
          /// question at once; on a 10- or 11-point scale a 1 answers 1 and a following 0 or 1 turns it
          /// into 10 or 11, and 0 followed by d answers d.
          function enterDigit(d) {
            if (digit !== null) {
              const open = digit;
              digit = null;
              const value = open.first * 10 + d;
              if (value >= (open.first === 1 ? 10 : 1) && value <= questions[open.q].points) return answer(open.q, value);
            }
            const q = firstUnanswered("scale");
            if (q < 0) return;
            const points = questions[q].points;
            if (points >= 10 && d <= 1) {
              digit = { q, first: d };
              if (d === 1) answer(q, 1);
              return;
            }
            if (d >= 1 && d <= points) answer(q, d);
          }
        },
      };
    }

    /// The trial screen's elements, laid out like the native window's (trial_screen.cpp).
    function trialView(display, step) {
      const root = element("div", "crowdlab-trial crowdlab-inter-trial");
      root.dataset.trial = String(step.trial);
      root.dataset.stimulus = step.stimulus;
      const header = element("div", "crowdlab-header", step.header);
      const area = element("div", "crowdlab-video-area");
      const video = element("video", "crowdlab-video");
      video.id = "crowdlab-video";
      const cross = element("div", "crowdlab-fixation");
      area.append(video, cross);
      const grid = element("div", "crowdlab-questions");
      const n = questions.length;
      const columns = Math.max(1, n <= 3 ? n : n === 4 ? 2 : 3);
      const rows = Math.ceil(n / columns);
      const columnMajor = rows === 2 && columns === 3;
      grid.style.gridTemplateColumns = `repeat(${columns}, minmax(0, 1fr)) auto`;
      const cells = questions.map((q, i) => {
        const r = columnMajor ? i % rows : Math.floor(i / columns);
        const c = columnMajor ? Math.floor(i / rows) : i % columns;
        const cell = element("div", "crowdlab-cell");
        cell.style.gridRow = String(r + 1);
        cell.style.gridColumn = String(c + 1);
        cell.append(element("div", "crowdlab-statement", q.text));
        const scale = element("div", q.kind === "yesno" ? "crowdlab-yesno" : "crowdlab-scale");
        if (q.kind === "yesno") {
          for (const [value, label] of [[1, "Yes (Y)"], [0, "No (N)"]]) {
            const b = element("button", "crowdlab-choice", label);
            b.type = "button";
            b.dataset.q = String(i);
            b.dataset.v = String(value);
            scale.append(b);
          }
        } else {
          // Every point labelled (labels.points), or, as natively, the end labels under the first and
          // the last circle, aligned with their outer edges.
          const perPoint = q.point_labels && q.point_labels.length === q.points;
          for (let v = 1; v <= q.points; v++) {
            const point = element("div", "crowdlab-point");
            const b = element("button", "crowdlab-circle", String(v));
            b.type = "button";
            b.dataset.q = String(i);
            b.dataset.v = String(v);
            point.append(b);
            if (perPoint) point.append(element("div", "crowdlab-point-label", q.point_labels[v - 1]));
            scale.append(point);
          }
          if (!perPoint) {
            const ends = element("div", "crowdlab-ends");
            ends.style.width = `calc(${q.points} * var(--crowdlab-step) - (var(--crowdlab-step) - var(--crowdlab-circle)))`;
            ends.append(element("span", "crowdlab-point-label", q.low_label || ""), element("span", "crowdlab-point-label", q.high_label || ""));
            cell.append(scale, ends);
          }
        }
        if (!cell.contains(scale)) cell.append(scale);
        grid.append(cell);
        return cell;
      });
      const nextButton = element("button", "crowdlab-next", timeline.texts.locked);
      nextButton.id = "crowdlab-next";
      nextButton.type = "button";
      nextButton.disabled = true;
      nextButton.style.gridColumn = String(columns + 1);
      nextButton.style.gridRow = `${rows} / ${rows + 1}`;
      grid.append(nextButton);
      root.append(header, area, grid);
      display.replaceChildren(root);
      const view = {
        header,
        video,
        showInterTrial(fixation) {
          root.classList.add("crowdlab-inter-trial");
          cross.hidden = !fixation;
        },
        showTrial() {
          root.classList.remove("crowdlab-inter-trial");
          cross.hidden = true;
          view.setLocked(true, []);
        },
        setLocked(locked, answers) {
          root.classList.toggle("crowdlab-locked", locked);
          for (const b of grid.querySelectorAll("button[data-q]")) b.disabled = locked;
          view.showAnswers(answers);
        },
        showAnswers(answers) {
          const locked = root.classList.contains("crowdlab-locked");
          const firstScale = questions.findIndex((q, i) => q.kind === "scale" && !answers[i]);
          const firstYesNo = questions.findIndex((q, i) => q.kind === "yesno" && !answers[i]);
          cells.forEach((cell, i) => {
            cell.classList.toggle("crowdlab-focus", !locked && (i === firstScale || i === firstYesNo));
            for (const b of cell.querySelectorAll("button[data-q]"))
              b.classList.toggle("crowdlab-selected", !!answers[i] && answers[i].response === Number(b.dataset.v));
          });
          const all = questions.length > 0 && questions.every((q, i) => !!answers[i]);
          nextButton.disabled = !all;
          nextButton.classList.toggle("crowdlab-ready", all);
          nextButton.textContent = all ? "Next (Enter)" : locked ? timeline.texts.locked : "Answer every question";
        },
      };
      return view;
    }
  }

  /// The end screen of the plan, then what a browser must do with the data: under JATOS submit them
  /// (and go to the completion link); otherwise offer the download and say what to do with it.
  function finish(jsPsych, store, study, plan) {
    const order = window.crowdlabTimeline.orders[store.data.order_of];
    const complete = store.data.records.length === order.length;
    store.data.complete = complete;
    store.data.sessions[store.data.sessions.length - 1].end_utc = new Date().toISOString();
    store.write();
    if (store.data.consent_record && !store.data.consent_record.consent.given) return declinedPage(store);
    if (!complete) return;
    const end = plan[plan.length - 1];
    const page = showMessage(end.title, end.text);
    transcript.push(shownScreen(end.screen, page));
    deliver(store, study, page);
  }

  /// A participant who declines is never sent to the completion link: on a panel such as Prolific that
  /// link submits the study as completed (and pays it), which a decline is not.
  function declinedPage(store) {
    const study = window.crowdlabTimeline.study;
    const page = showMessage("Thank you", "You did not agree to take part, so the study ends here.");
    if (study.completion_url)
      page.append(element("p", "crowdlab-body",
        "If you came from a participant panel, please return the study there; do not submit it as completed."));
    transcript.push({ screen: "declined" });
    deliver(store, study, page, { declined: true });
  }

  function deliver(store, study, page, { declined = false } = {}) {
    if (hasJatos()) {
      const saving = element("p", "crowdlab-hint", "Saving your answers...");
      saving.id = "crowdlab-saving";
      page.append(saving);
      store.pending.catch(() => {}).then(() => {
        // A decline ends the study run as unsuccessful without JATOS's end redirect (the study's End
        // Redirect URL is the completion link), and the page stays to say what to do.
        if (declined && jatos.endStudyAjax) return jatos.endStudyAjax(false, "consent declined")
          .catch(() => {}).then(() => { saving.textContent = "Your answer was saved. You may close this window."; });
        if (declined) return jatos.endStudy(false, "consent declined");
        if (study.completion_url) jatos.endStudyAndRedirect(study.completion_url);
        else jatos.endStudy();
      });
      return;
    }
    const file = new Blob([JSON.stringify(store.data, null, 1)], { type: "application/json" });
    const name = `${study.name}_${store.data.participant}.json`;
    page.append(
      element("p", "crowdlab-body",
        "Your answers are in a data file. Please download it with the button below and send it to the " +
          "experimenter as they asked you to (for example by e-mail or through the upload link you were given). " +
          "Then you may close this window."),
    );
    const link = element("a", "jspsych-btn", `Download the data (${name})`);
    link.id = "crowdlab-download";
    link.download = name;
    link.href = URL.createObjectURL(file);
    page.append(link);
    if (study.completion_url && !declined) {
      const back = element("a", "jspsych-btn", "Finish and return to the panel");
      back.id = "crowdlab-complete";
      back.href = study.completion_url;
      page.append(element("p", "crowdlab-body", "After the download:"), back);
    }
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
        // The study's id rule (participant_id.hpp, embedded in timeline.json): what import-web would
        // refuse never starts.
        if (!validId(timeline, id)) {
          const page = showMessage("Invalid participant id", `${idMessage(timeline, id)} Please contact the experimenter.`);
          page.id = "crowdlab-invalid-id";
          return;
        }
        run(timeline, id);
      })
      .catch((error) =>
        showMessage("The study could not start", `${error.message}\nOpen it through a web server (see docs/online.md), not as a file.`));
  }

  window.crowdlab = { fnv1a32, orderParticipant, transcript };
  if (hasJatos()) jatos.onLoad(start);
  else start();
})();
