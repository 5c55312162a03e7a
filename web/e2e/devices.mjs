// The phone and tablet profiles the layout and touch tests, the device
// screenshots and the first-draw measurement share: Playwright's device
// emulation (a touch screen, a mobile viewport) at the sizes the layout is
// checked at. A device scale factor of 1 keeps SwiftShader's pixels few; the
// layout is in CSS pixels either way.

/** Context options for a touch device of `width` × `height` CSS pixels. */
export function touchDevice(width, height) {
  return { viewport: { width, height }, screen: { width, height }, isMobile: true, hasTouch: true, deviceScaleFactor: 1 };
}

export const PHONE = touchDevice(390, 844);
export const PHONE_LANDSCAPE = touchDevice(844, 390);
export const SMALL_PHONE = touchDevice(360, 640);
export const TABLET = touchDevice(768, 1024);

/** The sizes the overlays are checked at: phones and a tablet as touch devices, the rest as desktops with a mouse. */
export const LAYOUT_SIZES = [
  { name: "360×640 phone", options: SMALL_PHONE },
  { name: "390×844 phone", options: PHONE },
  { name: "768×1024 tablet", options: TABLET },
  { name: "1280×800 desktop", options: { viewport: { width: 1280, height: 800 } } },
  { name: "1920×1080 desktop", options: { viewport: { width: 1920, height: 1080 } } },
];
