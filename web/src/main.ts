// Wiring only: the page's elements, the app made of its parts (app/app.ts),
// and the end-to-end tests' hook on pages opened with `?test`.

import "./style.css";
import "./layout.css";
import { App } from "./app/app";
import { pageElements } from "./app/page";
import { hasWebGL } from "./render/stage";
import { Messages } from "./ui/messages";

/** The address parameter that loads the tests' hook (testHook.ts says why it is not always there). */
const TEST_PARAM = "test";

const page = pageElements();

if (!hasWebGL()) {
  page.loading.hidden = true;
  new Messages(page.message, page.fatal).fatal(
    "WebGL is not available",
    "UP draws the balloon room with WebGL 2, which this browser (or its graphics driver) does not provide. " +
      "Try a current Chrome, Firefox or Safari, or enable hardware acceleration.",
  );
} else {
  const app = new App(page);
  if (new URLSearchParams(location.search).has(TEST_PARAM)) {
    void import("./app/testHook").then(({ installTestHook }) => installTestHook(app));
  }
  app.start();
}
